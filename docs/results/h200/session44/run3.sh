# Session 44 run3: run2's first part alone (the GPU suites at this
# session's code), for the device time left after seven failed starts.
# Pack: run2's (tools/gpu_pack.sh of 13bd194). Carried: .gl, .gpub, .assets,
# .peers/karim. Expectation: run2's (the suites pass).
source tools/gpu_run.sh
gpu_suites
gpu_finish
