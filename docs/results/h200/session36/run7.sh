# Session 36, run 7: run 6's machine code puts a binary BVH node step at
# about 90 instructions against the peer's 65, 24 of them the two slab
# tests' subtract and multiply per plane (the peer: one multiply-add).
# The probe (axis_slab.patch, build-gpu/octrace-axisslab): the binary BVH
# walk's box test as one multiply-add per plane with a margin per axis
# folded into two offsets (log 35's "per axis" form, measured then at
# -1.2% on this scene with 48 -> 56 registers, before logs 59-115).
# Expectations: expected.md ("run7.sh"). Carried: .gl, .gpub, .peers.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
X=build-gpu/octrace-axisslab
V=(--variant "base=" --variant "axis=BIN=$X")
AB_TIMEOUT=120 ab peer_bvh $P --accel bvh
ab peer_d1_bvh ${P/--depth 50/--depth 1} --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=120 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
$X render $P --accel bvh --pipeline-stats --json -q -o "$R/x.pfm" > "$R/axis_stats.json" 2> "$R/axis_stats.err"
$B render $P --accel bvh --pipeline-stats --json -q -o "$R/y.pfm" > "$R/base_stats.json" 2> "$R/base_stats.err"
cmp -s "$R/x.pfm" "$R/y.pfm" && echo "peer identical" >> "$T" || echo "peer DIFFERENT" >> "$T"
python3 - "$R/base_stats.json" "$R/axis_stats.json" >> "$T" <<'PY'
import json, sys
for f in sys.argv[1:]:
    try:
        j = json.load(open(f)); print(f.split("/")[-1], j.get("pipeline_statistics"))
    except Exception as e:
        print(f, "unreadable", e)
PY
rm -f "$R/x.pfm" "$R/y.pfm"
same_image s1m "$B" "$X" $S --spheres 1000000 --radius 0.1 --accel bvh
same_image s8000 "$B" "$X" $S --spheres 8000 --radius 0.1 --accel bvh
gpu_finish
