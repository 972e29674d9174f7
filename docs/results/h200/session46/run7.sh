# Session 46 run7: log 140's engine tail against the tail's existing
# knobs, no code changed: `--tail-fill` (auto: the threads the GPU holds
# at once, 270,336 here) smaller, so that levels keep packing the last
# paths longer, and `--tail-step` 2; the engine and the balloon, octree,
# fp32, the goals' settings, tools/ab_render.py 5 rounds, device time.
# Expectations in expected.md (run7).
source tools/gpu_run.sh
V=(--variant "auto=" --variant "fill65k=-- --tail-fill 65536" --variant "fill16k=-- --tail-fill 16384"
   --variant "fill4k=-- --tail-fill 4096" --variant "step2=-- --tail-step 2")
AB_ROUNDS=5
ab engine_fill $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_fill $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
