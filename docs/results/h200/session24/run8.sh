# Session 24 on the H200, run 8: `bench` of the meshes with run 7's
# binary (22020f6 + auto lanes 4 for meshes with the tail queue: the code
# of the commit that keeps it), on the machine still warm from run 7.
# Carried: .gl, .gpub (run 7's bin.txz), .assets.
source tools/gpu_run.sh >/dev/null 2>&1; timeout 150 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/bench_meshes.txt 2>&1; echo rc=$?; date -u; tail -6 $OUT/bench_meshes.txt
