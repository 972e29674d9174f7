# Log 50 at its commit on the H200: the GPU suites (the hard cases, the
# effects and accel tests) with the first batch a whole head dispatch.
# Carried: .gl, .gpub (bin.tgz of HEAD), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
timeout 60 build-gpu/tests/accel_test > $R/accel_test.txt 2>&1; echo "accel_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/accel_test.txt | tr '\n' ' ')" >> $T
timeout 400 build-gpu/tests/hardcases_test > $R/hardcases_test.txt 2>&1; echo "hardcases_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_test.txt | tr '\n' ' ')" >> $T
timeout 130 build-gpu/tests/effects_test > $R/effects_test.txt 2>&1; echo "effects_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/effects_test.txt | tr '\n' ' ')" >> $T
gpu_finish
