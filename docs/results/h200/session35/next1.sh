# Prepared in session 35 (its GPU time spent), for the next session with a
# GPU: the goals' rows at the session's last code (log 117's queue,
# ca148ff; the GPU suites ran at 3825c45 only): the GPU suites, the peer
# side by side with both structures, `bench`. Expectations: expected.md
# ("next1.sh"). Carried: .gl, .gpub, .assets, .peers.
source tools/gpu_run.sh
gpu_suites
peer_both
bench_goals
gpu_finish
