# Session 40 run3: the engine's octree at the grid's points within 48
# bytes a triangle (run2 found refs 16 with leaf 20 the best of its
# variants), and the balloon at that pair. Pack: 75b8957 (run1's).
# Carried: .gl, .gpub, .assets. Expectations in expected.md (run3).
source tools/gpu_run.sh
V=(--variant "default=" --variant "refs16leaf20=-- --octree-refs 16 --octree-leaf 20"
   --variant "refs16leaf19=-- --octree-refs 16 --octree-leaf 19" --variant "refs20leaf19=-- --octree-refs 20 --octree-leaf 19"
   --variant "refs20leaf20=-- --octree-refs 20 --octree-leaf 20" --variant "refs24leaf20=-- --octree-refs 24 --octree-leaf 20"
   --variant "refs32leaf20=-- --octree-refs 32 --octree-leaf 20")
AB_TIMEOUT=400 ab engine_in_bound $S --scene .assets/2CylinderEngine.glb --accel octree
V=(--variant "default=" --variant "refs16leaf20=-- --octree-refs 16 --octree-leaf 20")
AB_TIMEOUT=200 ab balloon $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
