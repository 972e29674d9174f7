# For the next session's first GPU run (session 52's device time ran out
# after the fetch's auto over spheres was committed; run8.sh did not
# start). Pack: tools/gpu_pack.sh (HEAD; no probe). Carry .gl, .gpub,
# .assets. Expectations (session 52, written before): render_test's
# tail-fetch case passes on the H100 (the fetch on and off the same bits;
# the auto takes a 4,196-sphere field); the 1M field's image with the
# auto identical to `--tail-fetch off`'s; `bench` of the goals: 8,000
# spheres' octree 5.3-5.4 ms and 1M's 6.4-6.5 ms (run 5's `on`), the BVH
# 4.10 and 4.03 ms, 488 and the meshes as run 4 (the engine 8.1-8.2 ms);
# the sweep of `--tail-fetch on` against off at 1,000 / 2,000 / 4,000
# spheres, where the auto's bound (4,096) was not measured: somewhere
# between run 5's 488 (1.008x octree, 1.027x BVH) and 8,000 (0.967x,
# 0.990x), the octree crossing 1.00x first; the hard cases 340/340.
# (Its dry run, tools/gpu_dry_run.sh: the GPU suites fail at once and the
# sweep's `--tail-fetch on` is refused on the CPU device, as they should.)
source tools/gpu_run.sh
render_cases '*TailFetch*' 120
"$B" render $S --spheres 1000000 --radius 0.1 --accel octree --tail-fetch off -q -o "$R/off.pfm"; "$B" render $S --spheres 1000000 --radius 0.1 --accel octree -q -o "$R/auto.pfm"
cmp -s "$R/off.pfm" "$R/auto.pfm" && echo "1M octree fetch auto vs off identical" >> "$T" || echo "1M octree fetch auto vs off DIFFERENT" >> "$T"
rm -f "$R/off.pfm" "$R/auto.pfm"
V=(--variant "off=-- --tail-fetch off" --variant "on=-- --tail-fetch on")
for n in 1000 2000 4000; do for a in octree bvh; do
  AB_TIMEOUT=100 ab spheres${n}_$a $S --spheres $n --radius 0.1 --accel $a
done; done
bench_goals
hardcases_shards 8 330
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
