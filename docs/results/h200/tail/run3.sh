# Log 49 on the H200: the GPU suites with the tail queue at its auto depth
# (3 in this build; the default became 2 after run2, the same code path).
# Carried: .gl, .gpub (bin.tgz as run2), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
timeout 240 build-gpu/tests/hardcases_test > $R/hardcases_test.txt 2>&1; echo "hardcases_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_test.txt | tr '\n' ' ')" >> $T
timeout 120 build-gpu/tests/accel_test > $R/accel_test.txt 2>&1; echo "accel_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/accel_test.txt | tr '\n' ' ')" >> $T
timeout 150 build-gpu/tests/effects_test > $R/effects_test.txt 2>&1; echo "effects_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/effects_test.txt | tr '\n' ' ')" >> $T
gpu_finish
