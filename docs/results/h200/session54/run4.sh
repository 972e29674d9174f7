# Session 54, run 4: not run (no machine came), and superseded: session
# 55's run1.sh runs its render_test tail-fetch case at a later HEAD, and
# run2.sh its Nsight Compute attempt (docs/results/h200/session55/). The
# script as it was planned is in git history (git show f6f2e68:docs/results/h200/session54/run4.sh).
echo "session54/run4.sh: superseded by docs/results/h200/session55/run1.sh and run2.sh" >&2
exit 2
