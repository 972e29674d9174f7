# Session 34, run 6 (the command given on the warm machine right after run
# 5, whose hard-case shard 0 reached gpu_suites' 240 s limit at its 118th
# case beside the other shards and the peer's build: 117 passed, the 118th
# cut off): shard 0 again, alone, the same pack (21a6322).
source tools/gpu_run.sh; export OCTRACE_TEST_DEVICE=gpu; mkdir -p build-gpu/tests/tmp; GTEST_TOTAL_SHARDS=4 GTEST_SHARD_INDEX=0 timeout 240 build-gpu/tests/hardcases_test > $OUT/hc0.txt 2>&1; echo rc=$?; grep -E "FAILED|PASSED|Failure" $OUT/hc0.txt | head; tail -5 $OUT/hc0.txt
