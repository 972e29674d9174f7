# Log 50 at its commit on the H200: the GPU suites (the hard cases, the
# effects and accel tests) with the first batch a whole head dispatch.
# Carried: .gl, .gpub (bin.tgz of HEAD), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
suite accel_test 60
suite hardcases_test 400
suite effects_test 130
gpu_finish
