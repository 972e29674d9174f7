# Session 34, run 7: lane_sample's entries between the sizes run 5 swept
# (64 = one an invocation, 40 registers; 128, the kept NVIDIA size, 47;
# 192, 57), from a probe of HEAD that reads them from OCTRACE_LANE_ENTRIES
# (entries_env.patch), on the peer's scene with both structures and 8,000
# spheres, with each size's pipeline statistics. Expectations: expected.md
# beside this script. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
E=build-gpu/octrace-entries
V=(--variant "e128=" --variant "e80=BIN=$E OCTRACE_LANE_ENTRIES=80" --variant "e96=BIN=$E OCTRACE_LANE_ENTRIES=96"
   --variant "e112=BIN=$E OCTRACE_LANE_ENTRIES=112" --variant "e144=BIN=$E OCTRACE_LANE_ENTRIES=144"
   --variant "e160=BIN=$E OCTRACE_LANE_ENTRIES=160")
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
for k in 80 96 112 144 160; do
  echo "entries $k octree: $(OCTRACE_LANE_ENTRIES=$k $E render $P --accel octree --pipeline-stats --json -q --out $R/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 300)" >> $T
done
rm -f $R/ps.png
AB_TIMEOUT=90 ab peer_octree $P --accel octree
AB_TIMEOUT=90 ab peer_bvh $P --accel bvh
AB_TIMEOUT=60 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
gpu_finish
