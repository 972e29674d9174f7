# Session 46 run4: run1's fp16 figures on the meshes side by side
# (tools/ab_render.py, the variants alternating, 7 rounds, device time):
# the balloon and the engine, octree, fp32 against fp16 and fp16-all.
# Expectations in expected.md (run4).
source tools/gpu_run.sh
V=(--variant "fp32=-- --precision fp32" --variant "fp16=-- --precision fp16" --variant "fp16all=-- --precision fp16-all")
AB_ROUNDS=7
ab balloon $S --scene .assets/balloon/scene.gltf --accel octree
ab engine $S --scene .assets/2CylinderEngine.glb --accel octree
gpu_finish
