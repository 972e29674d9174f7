# Session 47 run4: the fill and the subgroup stage's threshold around
# run3's best (32768 both), the engine and the balloon (octree), 5 rounds,
# device time; `auto` is the new default (fill and threshold 4 paths a
# resident warp: 33,792 on an H100). Expectations in expected.md (run4).
source tools/gpu_run.sh
V=(--variant "off=-- --tail-subgroup off" --variant "auto=" --variant "f32k=-- --tail-fill 32768 --tail-subgroup 32768"
   --variant "f16k=-- --tail-fill 16384 --tail-subgroup 16384" --variant "f65k=-- --tail-fill 65536 --tail-subgroup 65536"
   --variant "f32k_s16k=-- --tail-fill 32768 --tail-subgroup 16384"
   --variant "f32k_step2=-- --tail-fill 32768 --tail-subgroup 32768 --tail-step 2")
AB_ROUNDS=5
AB_TIMEOUT=200 ab engine_f $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=200 ab balloon_f $S --scene .assets/balloon/scene.gltf --accel octree
V=(--variant "off=-- --tail-subgroup off" --variant "auto=")
ab s488_f $S --spheres 488 --radius 0.1 --accel octree
ab s8000_f $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=150 ab s1m_f $S --spheres 1000000 --radius 0.1 --accel octree
gpu_finish
