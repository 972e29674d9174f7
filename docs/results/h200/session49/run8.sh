# Session 49 run8 (the session's last code: the review's list pass):
# render_test's camera-tile cases, the peer side by side, `bench` of the
# sphere rows, then the hard cases in eight shards of 180 s (the device
# time left to the session is short). Expectations in expected.md (run8).
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
timeout 100 build-gpu/tests/render_test --gtest_filter='*CameraTiles*' > "$R/render_test.txt" 2>&1
echo "render_test camera tiles: ok $(grep -c '^\[       OK \]' "$R/render_test.txt"), failed $(grep -c '^\[  FAILED  \] .*(' "$R/render_test.txt") $(gtest_result "$R/render_test.txt")" >> "$T"
peer_both
bench_logged spheres 100 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
for k in 0 1 2 3 4 5 6 7; do
  GTEST_TOTAL_SHARDS=8 GTEST_SHARD_INDEX=$k timeout 180 build-gpu/tests/hardcases_test > "$R/hardcases_$k.txt" 2>&1 &
done
wait
for f in "$R"/hardcases_*.txt; do
  echo "$(basename "$f"): ok $(grep -c '^\[       OK \]' "$f"), failed $(grep -c '^\[  FAILED  \] .*(' "$f") $(gtest_result "$f")" >> "$T"
done
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
