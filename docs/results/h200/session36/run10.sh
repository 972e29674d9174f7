# Session 36, run 10: the binary BVH walk in while-while form (Aila & Laine
# 2009; log 38 kept it for the octree walks only), a probe
# (bvh_while_while.patch, build-gpu/octrace-bvhww): node steps in an inner
# loop until the invocation holds a leaf, then the leaf. Expectations:
# expected.md ("run10.sh"). Carried: .gl, .gpub, .peers.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
X=build-gpu/octrace-bvhww
V=(--variant "base=" --variant "ww=BIN=$X")
AB_TIMEOUT=120 ab peer_bvh $P --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=120 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
$X render $P --accel bvh --pipeline-stats --json -q -o "$R/x.pfm" > "$R/ww_stats.json" 2> "$R/ww_stats.err"
echo "ww registers: $(python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['pipeline_statistics']; print(s['Register Count'], s['Binary Size'])" "$R/ww_stats.json" 2>&1)" >> "$T"
$B render $P --accel bvh -q -o "$R/y.pfm"
cmp -s "$R/x.pfm" "$R/y.pfm" && echo "peer identical" >> "$T" || echo "peer DIFFERENT" >> "$T"
rm -f "$R/x.pfm" "$R/y.pfm"
same_image s1m "$B" "$X" $S --spheres 1000000 --radius 0.1 --accel bvh
gpu_finish
