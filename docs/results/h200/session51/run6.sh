# Session 51, run 6: flags only, the engine at the goals' settings (HEAD's
# render code; the pack ae47877, whose render code is 544d289's): where the head's lanes and the tail's
# first depth stand now that the head is a third of the passes (log 145).
# Then the probe sum_reads.patch (log 150): the sum pass reads a pixel's
# values 8 at a time before adding them. Pack: tools/gpu_pack.sh
# sum=docs/results/h200/session51/sum_reads.patch (build-gpu/octrace-sum).
# Carry .gl, .gpub, .assets. Expectations: expected.md, run6.
source tools/gpu_run.sh
V=(--variant auto= --variant "lanes1=-- --sample-lanes 1" --variant "lanes4=-- --sample-lanes 4" --variant "lanes8=-- --sample-lanes 8" --variant "depth1=-- --tail-depth 1" --variant "sub24k=-- --tail-subgroup 24576")
AB_TIMEOUT=200 ab engine_flags $S --scene .assets/2CylinderEngine.glb --accel octree
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant head= --variant "sum=BIN=build-gpu/octrace-sum")
ab peer_sum $PEER --accel bvh
ab engine_sum $S --scene .assets/2CylinderEngine.glb --accel octree
same_image "peer sum" "$B" build-gpu/octrace-sum $PEER --accel bvh
timeout 100 python3 tools/dispatch_table.py --octrace "$B" --render "$PEER --accel bvh" --rounds 5 --out "$R/dispatch_peer_head.md" > /dev/null 2>&1; echo "dispatch head rc=$?" >> "$T"
timeout 100 python3 tools/dispatch_table.py --octrace build-gpu/octrace-sum --render "$PEER --accel bvh" --rounds 5 --out "$R/dispatch_peer_sum.md" > /dev/null 2>&1; echo "dispatch sum rc=$?" >> "$T"
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
