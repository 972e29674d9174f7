# Session 36, run 9: run 8's one-call head halved the head's machine code
# (24.7 -> 14.5 KB) and took it from 47 to 55 registers, for no time. Log
# 114 found NVIDIA's compiler budgets registers by the workgroup memory a
# pipeline declares (lane_sample's entries: 64 -> 40 registers, 96-144 ->
# 47, 192 -> 57 on the head of then). The probe
# (one_call_entries_env.patch: one_call.patch with session 34's
# entries_env.patch, OCTRACE_LANE_ENTRIES) sweeps the entries for the
# one-call head. Expectations: expected.md ("run9.sh"). Carried: .gl,
# .gpub, .peers.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
X=build-gpu/octrace-onecallenv
for e in 64 80 96 112 128 160 192; do
  OCTRACE_LANE_ENTRIES=$e $X render $P --accel bvh --pipeline-stats --json -q -o "$R/x.pfm" > "$R/stats_$e.json" 2> "$R/stats_$e.err"
  echo "entries $e: $(python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['pipeline_statistics']; print(s['Register Count'], s['Shared Memory Size'], s['Binary Size'])" "$R/stats_$e.json" 2>&1)" >> "$T"
done
rm -f "$R/x.pfm"
V=(--variant "base=" --variant "e64=BIN=$X OCTRACE_LANE_ENTRIES=64" --variant "e96=BIN=$X OCTRACE_LANE_ENTRIES=96" --variant "e128=BIN=$X OCTRACE_LANE_ENTRIES=128" --variant "e192=BIN=$X OCTRACE_LANE_ENTRIES=192")
AB_TIMEOUT=200 ab peer_bvh $P --accel bvh
AB_TIMEOUT=200 ab peer_octree $P --accel octree
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
gpu_finish
