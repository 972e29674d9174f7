# Session 52, run 6: the tail fetch with its auto over 4,096 spheres (log 152) on the
# H100: render_test's tail-queue and tail-fetch cases (the fetch on and
# off, bit for bit, through levels, fills, the subgroup stage, a small
# queue, fp16) beside the hard cases in eight shards (the meshes' cases
# run with the fetch's auto). Pack: tools/gpu_pack.sh (HEAD). Carry .gl,
# .gpub, .assets. Expectations: expected.md, run 6.
source tools/gpu_run.sh
gpu_tests
hardcases_shards 8 330 &
render_cases '*TailQueue*:*TailFetch*' 330
wait
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
