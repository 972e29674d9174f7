# Session 51, run 6: flags only, the engine at the goals' settings (HEAD's
# render code, the pack of run 1): where the head's lanes and the tail's
# first depth stand now that the head is a third of the passes (log 145).
# Carry .gl, .gpub, .assets. Expectations: expected.md, run6.
source tools/gpu_run.sh
V=(--variant auto= --variant "lanes1=-- --sample-lanes 1" --variant "lanes4=-- --sample-lanes 4" --variant "lanes8=-- --sample-lanes 8" --variant "depth1=-- --tail-depth 1" --variant "sub24k=-- --tail-subgroup 24576")
AB_TIMEOUT=200 ab engine_flags $S --scene .assets/2CylinderEngine.glb --accel octree
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
