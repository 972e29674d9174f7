# Session 52, run 1: the probes fetch.patch and fetchc.patch (the tail
# stage takes its level's paths from a counter, a bounce at a time, so
# that an invocation whose path ended takes the next at once; fetch: the
# subgroup's invocations stay in the loop until its last is done, one
# atomic a subgroup a round; fetchc: an invocation leaves when the level
# has no path left, one atomic an invocation a path), and flags that
# trade the engine's goal against its memory or precision. Pack:
# tools/gpu_pack.sh fetch=docs/results/h200/session52/fetch.patch
# fetchc=docs/results/h200/session52/fetchc.patch. Carry .gl, .gpub,
# .assets. Expectations: expected.md, run 1.
source tools/gpu_run.sh
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
ENG="$S --scene .assets/2CylinderEngine.glb --accel octree"
F=build-gpu/octrace-fetch; C=build-gpu/octrace-fetchc
same_image "engine fetch" "$B" $F $ENG
same_image "engine fetchc" "$B" $C $ENG
V=(--variant head= --variant "fetch=BIN=$F" --variant "fetchc=BIN=$C")
ab engine_fetch $ENG
ab balloon_fetch $S --scene .assets/balloon/scene.gltf --accel octree
AB_TIMEOUT=150 ab peer_fetch $PEER --accel bvh
same_image "peer fetch" "$B" $F $PEER --accel bvh
for v in head:$B fetch:$F fetchc:$C; do pipeline_stats "${v%%:*}" "${v#*:}" $ENG; done
for v in head:$B fetch:$F; do
  timeout 100 python3 tools/dispatch_table.py --octrace "${v#*:}" --render "$ENG" --rounds 5 --out "$R/dispatch_engine_${v%%:*}.md" > /dev/null 2>&1
  echo "dispatch engine ${v%%:*} rc=$?: $(grep -E '^\| (head|tail [0-9]|tail_subgroup 5|the passes) ' "$R/dispatch_engine_${v%%:*}.md" | cut -d'|' -f2,3,6 | tr '\n' ' ')" >> "$T"
done
V=(--variant auto= --variant "refs16=-- --octree-refs 16" --variant "fp16=-- --precision fp16")
AB_TIMEOUT=150 ab engine_flags $ENG
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
