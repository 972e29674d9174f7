# Session 20 on the H200, run 8 (expected.md): the engine with tail levels of
# steps 1, 4, 16, 47 against one tail, both structures.
source tools/gpu_run.sh
V=(--variant "one=" --variant "s47=-- --tail-step 47" --variant "s16=-- --tail-step 16" --variant "s4=-- --tail-step 4" --variant "s1=-- --tail-step 1")
AB_TIMEOUT=45 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=45 ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
gpu_finish
