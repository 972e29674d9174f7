# Session 42 run3: run2's whole-process comparison again with 15 rounds
# (run2's 7 had the engine +1.4% inside a 75 ms spread): a default render
# (1200x800, 10 spp) of the engine and the balloon, the copy leaves' auto
# against `--octree-refs 8`. Pack: run2's. Carried: .gl, .gpub, .assets.
# Expectations in expected.md (run3).
source tools/gpu_run.sh
V=(--variant "auto=" --variant "old=-- --octree-refs 8")
AB_ROUNDS=15 AB_METRIC=wall ab engine_wall_10spp $S --scene .assets/2CylinderEngine.glb --accel octree
AB_ROUNDS=15 AB_METRIC=wall ab balloon_wall_10spp $S --scene .assets/balloon/scene.gltf --accel octree
AB_ROUNDS=15 AB_METRIC=accel_build ab engine_build $S --scene .assets/2CylinderEngine.glb --accel octree
gpu_finish
