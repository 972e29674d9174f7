# Session 49 run3 (the same machine as run2, its NVIDIA shader cache warm
# from runs 1 and 2): run2 again with longer limits, since each case's
# pipelines were compiled cold there (the path tracer's SPIR-V changed)
# and every shard and render_test ran past 120 s. render_test's camera-tile
# and tail-queue cases alone (200 s), then the hard cases in eight shards
# (240 s each). As sent (one command line):
source tools/gpu_run.sh >/dev/null 2>&1; export OCTRACE_TEST_DEVICE=gpu; mkdir -p build-gpu/tests/tmp; ( time timeout 200 build-gpu/tests/render_test --gtest_filter='*CameraTiles*:*TailQueue*' ) > $OUT/render_test.txt 2>&1; grep -E "OK|FAIL|real" $OUT/render_test.txt; for k in 0 1 2 3 4 5 6 7; do GTEST_TOTAL_SHARDS=8 GTEST_SHARD_INDEX=$k timeout 240 build-gpu/tests/hardcases_test > "$OUT/hardcases_$k.txt" 2>&1 & done; wait; for k in 0 1 2 3 4 5 6 7; do echo "shard $k: ok $(grep -c '^\[       OK \]' $OUT/hardcases_$k.txt) failed $(grep -c '^\[  FAILED  \] .*(' $OUT/hardcases_$k.txt) $(grep -E '^\[  (PASSED|FAILED)' $OUT/hardcases_$k.txt | tr '\n' ' ')"; done; date -u
