# Session 36, run 8: run 6's head pipeline is 1,544 instructions (24.7 KB of
# machine code; the tail's 808, the peer's kernel 472): the walk and the
# bounce appear twice, because head_pass calls trace_path twice (up to the
# tail depth, and again to the path's end where the queue is full), and
# the driver inlines each call. The probe (one_call.patch,
# build-gpu/octrace-onecall): one call site in a loop of at most two
# trips. Expectations: expected.md ("run8.sh"). Carried: .gl, .gpub,
# .assets, .peers.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
X=build-gpu/octrace-onecall
V=(--variant "base=" --variant "onecall=BIN=$X")
AB_TIMEOUT=120 ab peer_bvh $P --accel bvh
AB_TIMEOUT=120 ab peer_octree $P --accel octree
ab peer_d1_bvh ${P/--depth 50/--depth 1} --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
for a in bvh octree; do
  $X render $P --accel $a --pipeline-stats --json -q -o "$R/x.pfm" > "$R/onecall_$a.json" 2> "$R/onecall_$a.err"
  $B render $P --accel $a --pipeline-stats --json -q -o "$R/y.pfm" > "$R/base_$a.json" 2> "$R/base_$a.err"
  cmp -s "$R/x.pfm" "$R/y.pfm" && echo "peer $a identical" >> "$T" || echo "peer $a DIFFERENT" >> "$T"
done
python3 - "$R"/base_bvh.json "$R"/onecall_bvh.json "$R"/base_octree.json "$R"/onecall_octree.json >> "$T" <<'PY'
import json, sys
for f in sys.argv[1:]:
    try:
        j = json.load(open(f)); print(f.split("/")[-1], j.get("pipeline_statistics"))
    except Exception as e:
        print(f, "unreadable", e)
PY
rm -f "$R/x.pfm" "$R/y.pfm"
same_image engine "$B" "$X" $S --scene .assets/2CylinderEngine.glb --accel octree
gpu_finish
