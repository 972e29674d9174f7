# Session 34, run 5: 21a6322 (lane_sample's NVIDIA size, log 114; the GPU's
# auto octree leaf over spheres 24, log 115) on the H100: the GPU suites,
# the peer side by side with both structures, `bench`, HEAD against the code
# before both (old: 75be938's renderer, shaders and tests), and lane_sample's
# size swept (slots: OCTRACE_LANE_SLOTS entries per invocation). The pack's
# COMMIT says which binary is which. Expectations: expected.md beside this
# script. Carried: .gl, .gpub, .assets, .peers.
source tools/gpu_run.sh
gpu_suites
peer peer_bvh --accel bvh
peer peer_octree --accel octree
V=(--variant "head=" --variant "old=BIN=build-gpu/octrace-old")
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
AB_TIMEOUT=100 ab peer_octree $P --accel octree
AB_TIMEOUT=100 ab peer_bvh $P --accel bvh
AB_TIMEOUT=60 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=60 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
V=(--variant "x2=" --variant "x1=BIN=build-gpu/octrace-slots OCTRACE_LANE_SLOTS=1"
   --variant "x3=BIN=build-gpu/octrace-slots OCTRACE_LANE_SLOTS=3" --variant "x4=BIN=build-gpu/octrace-slots OCTRACE_LANE_SLOTS=4")
AB_TIMEOUT=120 ab slots_peer_octree $P --accel octree
AB_TIMEOUT=120 ab slots_peer_bvh $P --accel bvh
for k in 1 3 4; do
  echo "slots x$k octree: $(OCTRACE_LANE_SLOTS=$k build-gpu/octrace-slots render $P --accel octree --pipeline-stats --json -q --out $R/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 300)" >> $T
done
echo "head octree: $($B render $P --accel octree --pipeline-stats --json -q --out $R/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 300)" >> $T
rm -f $R/ps.png
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 > $OUT/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E " ms" $OUT/spheres.log | grep -v "^#" | tail -6 >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E "rays/s$" $OUT/meshes.log >> $T
gpu_finish
