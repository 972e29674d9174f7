# Session 25 on the H200, run 6 (expected.md): `bench` of the meshes and
# the GPU suites with the session's final code (3075a2e). Carried: .gl,
# .gpub (bin.txz: app/octrace and tests = 3075a2e, octrace-base = cd9c403),
# .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
M="--device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb"
timeout 150 $B bench $M > $OUT/bench_meshes.txt 2>&1; echo "bench rc=$?" >> $T; grep -E "rays/s$" $OUT/bench_meshes.txt >> $T
same_image engine_bvh $A $B $S --scene .assets/2CylinderEngine.glb --accel bvh
gpu_suites
gpu_finish
