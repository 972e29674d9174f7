# Session 44 run1: session 43's run5, which did not run there (log 138's
# question for the sparse sphere fields: `bench` of 488 and 8,000 spheres,
# r = 0.1, at the defaults and with `--octree-refs` 4, 16 and 32), as it is.
# Pack: session 43 run2's (90f376e: the render code of 543a18f). Carried:
# .gl, .gpub, .assets. Expectations in expected.md (run1).
bash docs/results/h200/session43/run5.sh
