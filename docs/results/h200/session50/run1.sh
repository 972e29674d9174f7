# Session 50 run1: the probes sg1 and tail32 against HEAD on the meshes,
# and the engine's passes dispatch by dispatch. As first written the run
# also tabled the balloon, the engine with the BVH, the peer's scene and 488
# spheres, timed the cost of --dispatch-times, sg1b, sg1's threshold and
# render_test's cases: cut to this as 21 calls for a machine got none and
# spent all but four minutes of the session's device time (the history of
# this file and of expected.md keeps each form). Expectations in
# expected.md (run1).
source tools/gpu_run.sh
# sg1 (sg1.patch): the subgroup stage's workgroup one subgroup, a path's,
# instead of 64 invocations (two paths on NVIDIA's warps of 32); tail32
# (tail32.patch, on sg1): the tail levels' workgroups a warp too.
G=build-gpu/octrace-sg1; W=build-gpu/octrace-tail32
V=(--variant base= --variant sg1=BIN=$G --variant tail32=BIN=$W)
ab engine_probes $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_probes $S --scene .assets/balloon/scene.gltf --accel octree
same_image "engine sg1" "$B" "$G" $S --scene .assets/2CylinderEngine.glb --accel octree
timeout 60 python3 tools/dispatch_table.py --octrace "$B" --render "$S --scene .assets/2CylinderEngine.glb --accel octree" --out "$OUT/dispatch_engine.md" > "$R/dispatch_engine.log" 2>&1
echo "dispatch engine rc=$?" >> "$T"
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
