# Session 54, run 2 (session 53's, which no machine ran): the rest of session 52's next1.sh (a sweep of
# `--tail-fetch on` against off at 1,000 / 2,000 / 4,000 spheres, `bench`
# of the goals) and the probe copies.patch on the peer's scene and on
# the 1M field's tree with its surface cells (`--octree-surfaces on`, the
# tree a render of 600 spp or more builds). Pack: as run 1's. Carry .gl, .gpub, .assets. Expectations: expected.md, runs 1
# and 2. Last, `--walk-stats` of 8,000 spheres with both structures: what
# a query does on the H100, and how busy its warps' lanes are at each
# step (the slots' counts).
# Session 54: the copies probe's items dropped (run 1: 1.008x slower at 8,000 and 1M).
source tools/gpu_run.sh
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
C=build-gpu/octrace-copies
V=(--variant "off=-- --tail-fetch off" --variant "on=-- --tail-fetch on")
for n in 1000 2000 4000; do for a in octree bvh; do
  AB_TIMEOUT=100 ab spheres${n}_$a $S --spheres $n --radius 0.1 --accel $a
done; done
bench_goals
for a in octree bvh; do
  "$B" render $S --spheres 8000 --radius 0.1 --accel $a --walk-stats --json -q -o "$R/w.pfm" > "$R/walk_8000_$a.json" 2>&1
  echo "walk-stats 8000 $a: $(python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["walk"]; q=w["queries"]; print({k: round(v / q, 3) for k, v in w.items()})' "$R/walk_8000_$a.json" 2>&1 | head -c 600)" >> "$T"
done
rm -f "$R/w.pfm"
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
