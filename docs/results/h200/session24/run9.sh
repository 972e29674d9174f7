# Session 24 on the H200, run 9: the GPU suites with the session's final
# code (ea98f07: logs 68, 69 and 71): the hard cases, accel_test, the
# tail-queue case and render_test's instancing cases. Expected: all pass.
# Carried: .gl, .gpub (bin.txz: app/octrace, tests), .assets. Prelude:
# tools/gpu_run.sh.
source tools/gpu_run.sh
gpu_suites
OCTRACE_TEST_DEVICE=gpu timeout 100 build-gpu/tests/render_test --gtest_filter='*InstancesRenderAsCopies*:*OneInstance*:*Lanes*' > $R/render_test_instances.txt 2>&1
echo "render_test instances and lanes rc=$? $(gtest_result $R/render_test_instances.txt)" >> $T
gpu_finish
