# Session 54, run 1 (session 53's, which no machine ran): the checks of HEAD's render code (f4286d4's: the tail
# fetch with its auto over spheres from 4,096, its first fetch and the
# loop's in one place) that were not run on the GPU: render_test's
# tail-fetch case, the 1M field's image under the auto, the engine's
# registers, the hard cases; and the probe copies.patch on the sparse
# fields (after run 1 was split from run 2 when the device time left
# made one call likelier than two). Pack: tools/gpu_pack.sh
# copies=docs/results/h200/session53/copies.patch at HEAD (repack: since
# 4f22431's pack the loop-limit check was added, off on GPUs). In order of what matters most, should the call's
# time limit cut it. Carry .gl, .gpub, .assets. Expectations:
# expected.md, runs 1 and 2.
source tools/gpu_run.sh
C=build-gpu/octrace-copies
render_cases '*TailFetch*:*PathsCutShort*' 120
same_image "8000 octree copies" "$B" $C $S --spheres 8000 --radius 0.1 --accel octree
V=(--variant head= --variant "copies=BIN=$C")
ab spheres8000_octree $S --spheres 8000 --radius 0.1 --accel octree
"$B" render $S --spheres 1000000 --radius 0.1 --accel octree --tail-fetch off -q -o "$R/off.pfm"; "$B" render $S --spheres 1000000 --radius 0.1 --accel octree -q -o "$R/auto.pfm"
cmp -s "$R/off.pfm" "$R/auto.pfm" && echo "1M octree fetch auto vs off identical" >> "$T" || echo "1M octree fetch auto vs off DIFFERENT" >> "$T"
rm -f "$R/off.pfm" "$R/auto.pfm"
hardcases_shards 8 330
same_image "1M octree copies" "$B" $C $S --spheres 1000000 --radius 0.1 --accel octree
ab spheres1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
ab spheres488_octree $S --spheres 488 --radius 0.1 --accel octree
pipeline_stats engine "$B" $S --scene .assets/2CylinderEngine.glb --accel octree
for v in head:$B copies:$C; do pipeline_stats "${v%%:*}" "${v#*:}" $S --spheres 8000 --radius 0.1 --accel octree; done
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
