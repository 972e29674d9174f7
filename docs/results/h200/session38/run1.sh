# Session 38, run 1: log 126 (the octree's top level over the spheres'
# surfaces in a dense field) on the GPU. The pack: build-gpu/app/octrace =
# c0b54d6 (log 126), build-gpu/octrace-base = the same with
# before_log126.patch (a002be6's trees). Expectations: expected.md. Carried:
# .gl, .gpub. About 7 minutes (the device time left: 17 minutes).
source tools/gpu_run.sh
# The GPU suites at log 126 (accel_test's dense_overlapping renders the
# octree over the clipped surfaces against brute force; the hard cases'
# dense_overlapping_field in every accel and precision).
gpu_suites
# The same image: the walk finds the same nearest hit with either tree.
same_image "s1m octree base/new" "$A" "$B" $S --spheres 1000000 --radius 0.1 --accel octree
# Device time of the passes, before and after, alternating.
V=(--variant base=BIN=$A --variant new=)
ab s1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
"$B" render $S --spheres 1000000 --radius 0.1 --accel octree --walk-stats -q -o "$R/w.pfm" > "$R/walk_new.txt" 2>&1
"$A" render $S --spheres 1000000 --radius 0.1 --accel octree --walk-stats -q -o "$R/w.pfm" > "$R/walk_base.txt" 2>&1
grep -hE "^(octree|walk|times)" "$R/walk_base.txt" "$R/walk_new.txt" >> "$T"
# The octree at 10M, before and after (bench warms up first, log 55).
B=$A bench_logged spheres10m_octree_base 120 " ms" --accel octree --spheres 10000000 --radius 0.1
bench_logged spheres10m_octree 120 " ms" --accel octree --spheres 10000000 --radius 0.1
gpu_finish
