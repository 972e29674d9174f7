# Session 47 run2: the GPU suites at the subgroup stage's code (the hard
# cases in four shards, accel_test, render_test's tail-queue case, which
# now checks the stage bit for bit). `bench` of the meshes moved to run4.
# Expectations in expected.md (run2).
source tools/gpu_run.sh
gpu_suites
gpu_finish
