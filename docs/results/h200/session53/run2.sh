# Session 53, run 2: the probe copies.patch (the octree over spheres alone
# holds a copy of each leaf slot's sphere after the scene's spheres, at
# sphere_count + k, and the leaf test reads it beside refs[k] instead of
# after it: two independent loads where there were two dependent ones).
# Pack: tools/gpu_pack.sh copies=docs/results/h200/session53/copies.patch.
# Carry .gl, .gpub, .assets. Expectations: expected.md, run 2.
source tools/gpu_run.sh
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
C=build-gpu/octrace-copies
same_image "8000 octree copies" "$B" $C $S --spheres 8000 --radius 0.1 --accel octree
same_image "1M octree copies" "$B" $C $S --spheres 1000000 --radius 0.1 --accel octree
same_image "peer octree copies" "$B" $C $PEER --accel octree
for v in head:$B copies:$C; do pipeline_stats "${v%%:*}" "${v#*:}" $S --spheres 8000 --radius 0.1 --accel octree; done
V=(--variant head= --variant "copies=BIN=$C")
ab spheres488_octree $S --spheres 488 --radius 0.1 --accel octree
ab spheres8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab spheres1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
AB_TIMEOUT=150 ab peer_octree $PEER --accel octree
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
