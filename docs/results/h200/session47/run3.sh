# Session 47 run3: the subgroup stage's threshold against the tail fill,
# the engine and the balloon (octree), tools/ab_render.py 5 rounds,
# device time. Expectations in expected.md (run3).
source tools/gpu_run.sh
V=(--variant "off=-- --tail-subgroup off" --variant "s32k=-- --tail-subgroup 32768"
   --variant "s65k=-- --tail-subgroup 65536" --variant "s131k=-- --tail-subgroup 131072"
   --variant "s270k=-- --tail-subgroup 270336" --variant "f8k=-- --tail-fill 8448 --tail-subgroup 8448"
   --variant "f32k=-- --tail-fill 32768 --tail-subgroup 32768")
AB_ROUNDS=5
AB_TIMEOUT=200 ab engine_thr $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=200 ab balloon_thr $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
