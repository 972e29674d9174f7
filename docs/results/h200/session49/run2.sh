# Session 49 run2: `bench` of the sphere fields (the goals' rows; the
# camera's tiles on by auto at 488 and 8,000, off at 1M), then the hard
# cases on the H100 in eight shards and render_test's camera-tile and
# tail-queue cases, each with a 120 s limit.
source tools/gpu_run.sh
bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for k in 0 1 2 3 4 5 6 7; do
  GTEST_TOTAL_SHARDS=8 GTEST_SHARD_INDEX=$k timeout 120 build-gpu/tests/hardcases_test > "$R/hardcases_$k.txt" 2>&1 &
done
wait
timeout 120 build-gpu/tests/render_test --gtest_filter='*CameraTiles*:*TailQueue*' > "$R/render_test.txt" 2>&1
for f in "$R"/hardcases_*.txt "$R/render_test.txt"; do
  echo "$(basename "$f"): ok $(grep -c '^\[       OK \]' "$f"), failed $(grep -c '^\[  FAILED  \] .*(' "$f") $(gtest_result "$f")" >> "$T"
done
gpu_finish
