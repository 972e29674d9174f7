# Session 35, run 4: the GPU suites at 3825c45 (cb8d691's code: log 116's lanes
# rule), on the machine run 3 left warm. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
gpu_suites
gpu_finish
