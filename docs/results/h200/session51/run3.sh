# Session 51, run 3: the hard cases on the GPU at HEAD's code (544d289's
# render code, logs 146 and 147 in), 8 shards. Pack: as run1. Carry .gl,
# .gpub, .assets. Expectations: expected.md, run3.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
hardcases_shards 8 240
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
