# Session 47 run4: the fill and the subgroup stage's threshold around
# run3's best (32768 both), the engine and the balloon (octree), 5 rounds,
# device time; `auto` is the new default (fill and threshold 4 paths a
# resident warp: 33,792 on an H100); then the sphere fields off against
# auto, and `bench` of the meshes (the glTF goal's rays/s, run2's second
# part), then the GPU suites (run2, merged in: one machine start fewer).
# Expectations in expected.md (run4, run2).
source tools/gpu_run.sh
V=(--variant "off=-- --tail-subgroup off" --variant "auto="
   --variant "f16k=-- --tail-fill 16384 --tail-subgroup 16384" --variant "f65k=-- --tail-fill 65536 --tail-subgroup 65536")
AB_ROUNDS=5
AB_TIMEOUT=150 ab engine_f $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=150 ab balloon_f $S --scene .assets/balloon/scene.gltf --accel octree
V=(--variant "off=-- --tail-subgroup off" --variant "auto=")
ab s488_f $S --spheres 488 --radius 0.1 --accel octree
ab s8000_f $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=120 ab s1m_f $S --spheres 1000000 --radius 0.1 --accel octree
bench_logged meshes 120 "rays/s$" --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
gpu_suites
gpu_finish
