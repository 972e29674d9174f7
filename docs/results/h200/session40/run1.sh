# Session 40 run1: the GPU suites at the session's test code (the hard
# cases with brute force in fp32 only, 340 tests in four shards; accel_test;
# render_test's tail-queue cases) and render_test's reconfigure cases (their
# switches reordered this session). Pack: tools/gpu_pack.sh (75b8957).
# Carried: .gl, .gpub. Expectations in expected.md (run1).
source tools/gpu_run.sh
gpu_suites
export OCTRACE_TEST_DEVICE=gpu
timeout 200 build-gpu/tests/render_test --gtest_filter='*Reconfigure*' > "$R/render_test_reconfigure.txt" 2>&1
echo "render_test reconfigure rc=$? $(gtest_result "$R/render_test_reconfigure.txt")" >> "$T"
gpu_finish
