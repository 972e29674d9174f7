# Session 16 on the H200, run 2: the whole hard-case suite on the GPU
# (67 cases x (octree and BVH x fp32, fp16, fp16-all) + bvh4: 469 tests),
# the code as it stands (build-gpu/tests/hardcases_test of run 1's bin.tgz).
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
suite hardcases_test 500
gpu_finish
