# Session 51, run 2: the probe tail_cells.patch (log 149): the tail queue
# in buckets by the ray's direction octant and its origin's cell in a
# grid of C^3 over the top-level root box, C from OCTRACE_PROBE_TAIL_CELLS
# (0: the dense queue of HEAD, through the probe's code). Pack: as run1
# (build-gpu/octrace-cells is 544d289 + the patch). Carry .gl, .gpub,
# .assets. Expectations: expected.md, run2.
source tools/gpu_run.sh
P=build-gpu/octrace-cells
for c in 4; do printf '#!/bin/sh\nOCTRACE_PROBE_TAIL_CELLS=%s exec %s "$@"\n' $c "$PWD/$P" > build-gpu/octrace-c$c; chmod +x build-gpu/octrace-c$c; done
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant head= --variant "c0=BIN=$P" --variant "c1=BIN=$P OCTRACE_PROBE_TAIL_CELLS=1" --variant "c2=BIN=$P OCTRACE_PROBE_TAIL_CELLS=2" --variant "c4=BIN=$P OCTRACE_PROBE_TAIL_CELLS=4")
ab engine_cells $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_cells $S --scene .assets/balloon/scene.gltf --accel octree
ab peer_cells $PEER --accel bvh
same_image "engine c4" "$B" build-gpu/octrace-c4 $S --scene .assets/2CylinderEngine.glb --accel octree
same_image "peer c4" "$B" build-gpu/octrace-c4 $PEER --accel bvh
timeout 120 python3 tools/dispatch_table.py --octrace build-gpu/octrace-c4 --render "$S --scene .assets/2CylinderEngine.glb --accel octree" --rounds 5 --out "$R/dispatch_engine_c4.md" > /dev/null 2>&1; echo "dispatch c4 rc=$?" >> "$T"
timeout 120 python3 tools/dispatch_table.py --octrace "$B" --render "$S --scene .assets/2CylinderEngine.glb --accel octree" --rounds 5 --out "$R/dispatch_engine_head.md" > /dev/null 2>&1; echo "dispatch head rc=$?" >> "$T"
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
