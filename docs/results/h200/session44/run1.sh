# Session 44 run1 (session 43's run5, not run there): log 138's question for the sparse sphere fields: `bench`
# of 488 and 8,000 spheres (r = 0.1) at the defaults (octree and BVH) and
# the octree with the budget given (`--octree-refs 4`, 16, 32).
# Pack: session 43 run2's (90f376e: the render code of HEAD, 543a18f). Carried: .gl, .gpub, .assets.
# Expectations in expected.md (run1).
source tools/gpu_run.sh
bench_logged spheres 90 " ms" --accel octree,bvh --spheres 488,8000 --radius 0.1
for r in 4 16 32; do
  bench_logged spheres_refs$r 90 " ms" --accel octree --spheres 488,8000 --radius 0.1 --octree-refs $r
done
for f in $OUT/spheres*.log; do echo "$(basename $f): $(grep -E '^\| [0-9]' $f | tr '\n' ' ')" >> $T; done
gpu_finish
