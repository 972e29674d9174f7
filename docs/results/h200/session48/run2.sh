# Session 48 run2: the engine's tail settings around the kept split node
# step (device time left after run1: 304 s): tail depth 3, tail step 2,
# fill = threshold = 24,576, against auto. Expectations in expected.md (run2).
source tools/gpu_run.sh
V=(--variant "auto=" --variant "depth3=-- --tail-depth 3" --variant "step2=-- --tail-step 2"
   --variant "f24k=-- --tail-subgroup 24576 --tail-fill 24576")
ab engine_tail $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_tail $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
