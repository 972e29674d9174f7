# Session 49 run7 (a38bd69's pack, the session's final render code): the
# meshes' camera rays against their whole paths (device time, 5 rounds,
# one process per variant), then the hard cases in eight shards of 400 s.
# Expectations in expected.md (run7).
source tools/gpu_run.sh
V=(--variant "depth50=" --variant "depth1=-- --depth 1" --variant "depth2=-- --depth 2")
ab engine_depth $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_depth $S --scene .assets/balloon/scene.gltf --accel octree
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for k in 0 1 2 3 4 5 6 7; do
  GTEST_TOTAL_SHARDS=8 GTEST_SHARD_INDEX=$k timeout 400 build-gpu/tests/hardcases_test > "$R/hardcases_$k.txt" 2>&1 &
done
wait
for f in "$R"/hardcases_*.txt; do
  echo "$(basename "$f"): ok $(grep -c '^\[       OK \]' "$f"), failed $(grep -c '^\[  FAILED  \] .*(' "$f") $(gtest_result "$f")" >> "$T"
done
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
