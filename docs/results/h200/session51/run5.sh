# Session 51, run 5: bench of the goals at HEAD (544d289 render code). Pack: as run1.
source tools/gpu_run.sh
bench_goals
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
