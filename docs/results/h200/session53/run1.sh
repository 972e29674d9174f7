# Session 53, run 1: session 52's next1.sh (the tail fetch at HEAD on the
# GPU: render_test's tail-fetch case, the 1M field's image under the
# auto, a sweep of `--tail-fetch on` against off at 1,000 / 2,000 /
# 4,000 spheres, `bench` of the goals, the hard cases) and the engine's
# registers at HEAD. Pack: tools/gpu_pack.sh copies=docs/results/h200/session53/copies.patch (4f22431: the render code of f4286d4). Carry .gl,
# .gpub, .assets. Expectations: expected.md, run 1.
source tools/gpu_run.sh
pipeline_stats engine "$B" $S --scene .assets/2CylinderEngine.glb --accel octree
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
