# Session 41 run5: the whole process of `render` with `--octree-refs 12
# --octree-leaf 20` given as flags (one build) against the old settings
# (`--octree-refs 8 --octree-leaf 10`), the engine and the balloon, 10 spp.
# Pack: run3's (1659097: its autos are overridden by both flags). Carried:
# .gl, .gpub, .assets. Expectations in expected.md (run5).
source tools/gpu_run.sh
V=(--variant "old=-- --octree-refs 8 --octree-leaf 10" --variant "refs12leaf20=-- --octree-refs 12 --octree-leaf 20")
AB_ROUNDS=7 AB_METRIC=wall AB_TIMEOUT=200 ab engine_wall_10spp $S --scene .assets/2CylinderEngine.glb --accel octree
AB_ROUNDS=7 AB_METRIC=wall AB_TIMEOUT=200 ab balloon_wall_10spp $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
