# Session 50 run1: where the passes' time goes, dispatch by dispatch
# (render --dispatch-times through tools/dispatch_table.py) on the goals'
# scenes; its cost against the same render without it; the probe sg1
# against HEAD (render_test's cases moved to run 2: the run's 600 s).
# Expectations in expected.md (run1).
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
table() {
  local name=$1; shift
  timeout 120 python3 tools/dispatch_table.py --octrace "$B" --render "$*" --out "$OUT/dispatch_$name.md" > "$R/dispatch_$name.log" 2>&1
  echo "dispatch $name rc=$?" >> "$T"
}
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
table engine $S --scene .assets/2CylinderEngine.glb --accel octree
table balloon $S --scene .assets/balloon/scene.gltf --accel octree
table engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
table peer_bvh $PEER --accel bvh
table peer_octree $PEER --accel octree
table spheres488 $S --spheres 488 --radius 0.1 --accel octree
V=(--variant base= --variant timed="-- --dispatch-times")
ab engine_timed $S --scene .assets/2CylinderEngine.glb --accel octree
ab peer_timed $PEER --accel bvh
# The probe sg1 (sg1.patch): the subgroup stage's workgroup one subgroup,
# a path's, instead of 64 invocations (two paths on NVIDIA's warps of 32).
G=build-gpu/octrace-sg1
V=(--variant base= --variant sg1=BIN=$G)
ab engine_sg1 $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_sg1 $S --scene .assets/balloon/scene.gltf --accel octree
same_image "engine sg1" "$B" "$G" $S --scene .assets/2CylinderEngine.glb --accel octree
same_image "balloon sg1" "$B" "$G" $S --scene .assets/balloon/scene.gltf --accel octree
# sg1b: sg1 with the stage's workgroup array (lane_sample, unused there)
# at half the entries, as the 2-per-invocation rule of log 114 would have it.
V=(--variant base= --variant sg1=BIN=$G --variant sg1b=BIN=build-gpu/octrace-sg1b)
ab engine_sg1b $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_sg1b $S --scene .assets/balloon/scene.gltf --accel octree
# tail32 (tail32.patch, on sg1): the tail levels' workgroups a warp too.
W=build-gpu/octrace-tail32
V=(--variant base= --variant sg1=BIN=$G --variant tail32=BIN=$W)
ab engine_tail32 $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_tail32 $S --scene .assets/balloon/scene.gltf --accel octree
ab peer_tail32 $PEER --accel bvh
same_image "engine tail32" "$B" "$W" $S --scene .assets/2CylinderEngine.glb --accel octree
same_image "peer tail32" "$B" "$W" $PEER --accel bvh
V=(--variant sg1=BIN=$G --variant sg1_16k="BIN=$G -- --tail-subgroup 16384 --tail-fill 16384" --variant sg1_67k="BIN=$G -- --tail-subgroup 67584 --tail-fill 67584")
ab engine_sg1_threshold $S --scene .assets/2CylinderEngine.glb --accel octree
B0=$B; B=$G; table engine_sg1 $S --scene .assets/2CylinderEngine.glb --accel octree; B=$B0
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
