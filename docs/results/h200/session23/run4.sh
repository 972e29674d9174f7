# Session 23 on the H200, run 4 (expected.md): the kept VT2 (vt's inline
# form): the GPU suites and `bench` of the meshes. Carried: .gl, .gpub
# (bin.txz: app/octrace, tests, octrace-base), .assets. Prelude:
# tools/gpu_run.sh.
source tools/gpu_run.sh
gpu_suites
timeout 150 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $R/bench_meshes.txt 2>&1
echo "bench meshes rc=$?" >> $T; grep -E '^\|' $R/bench_meshes.txt | tail -5 >> $T
gpu_finish
