# Session 52, run 7: `bench` of the goals with the tail fetch's auto over
# 4,096 spheres (log 152), and its auto against `--tail-fetch off` where
# it now takes spheres alone (8,000 and 1M, both structures), the images
# the same; the peer's scene (488 spheres: the auto stays off) against
# the peer. Pack: tools/gpu_pack.sh (HEAD). Carry .gl, .gpub, .assets.
# Expectations: expected.md, run 7.
source tools/gpu_run.sh
V=(--variant "off=-- --tail-fetch off" --variant auto=)
for n in 8000 1000000; do for a in octree bvh; do
  AB_TIMEOUT=120 ab spheres${n}_$a $S --spheres $n --radius 0.1 --accel $a
done; done
"$B" render $S --spheres 1000000 --radius 0.1 --accel octree --tail-fetch off -q -o "$R/off.pfm"; "$B" render $S --spheres 1000000 --radius 0.1 --accel octree -q -o "$R/auto.pfm"
cmp -s "$R/off.pfm" "$R/auto.pfm" && echo "1M octree fetch auto vs off identical" >> "$T" || echo "1M octree fetch auto vs off DIFFERENT" >> "$T"
rm -f "$R/off.pfm" "$R/auto.pfm"
bench_goals
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
