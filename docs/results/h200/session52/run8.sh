# Session 52, run 8: what runs 6 and 7 would have checked, in the device
# time left after refused calls (342 s): render_test's tail-fetch case on
# the H100 (the fetch on and off the same bits, and the auto now taking a
# 4,196-sphere field), the 1M field's image with the auto against
# `--tail-fetch off`, and `bench` of the sphere rows. Pack: tools/gpu_pack.sh
# (HEAD, run 6's). Carry .gl, .gpub, .assets. Expectations: expected.md,
# runs 6 and 7.
source tools/gpu_run.sh
render_cases '*TailFetch*' 120
"$B" render $S --spheres 1000000 --radius 0.1 --accel octree --tail-fetch off -q -o "$R/off.pfm"; "$B" render $S --spheres 1000000 --radius 0.1 --accel octree -q -o "$R/auto.pfm"
cmp -s "$R/off.pfm" "$R/auto.pfm" && echo "1M octree fetch auto vs off identical" >> "$T" || echo "1M octree fetch auto vs off DIFFERENT" >> "$T"
rm -f "$R/off.pfm" "$R/auto.pfm"
bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
