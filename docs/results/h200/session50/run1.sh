# Session 50 run1: where the passes' time goes, dispatch by dispatch
# (render --dispatch-times through tools/dispatch_table.py) on the goals'
# scenes; its cost against the same render without it; the probes sg1,
# sg1b and tail32 against HEAD (render_test's cases left to a later run;
# the balloon's table, the peer's scene, 488 spheres, the cost of the
# timestamps and sg1's own table too: the session's device time was short
# after ten calls got no machine).
# Expectations in expected.md (run1).
source tools/gpu_run.sh
table() {
  local name=$1; shift
  timeout 120 python3 tools/dispatch_table.py --octrace "$B" --render "$*" --out "$OUT/dispatch_$name.md" > "$R/dispatch_$name.log" 2>&1
  echo "dispatch $name rc=$?" >> "$T"
}
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
table engine $S --scene .assets/2CylinderEngine.glb --accel octree
# The probes: sg1 (sg1.patch), the subgroup stage's workgroup one subgroup,
# a path's, instead of 64 invocations (two paths on NVIDIA's warps of 32);
# sg1b (sg1b.patch), sg1 with the stage's workgroup array halved; tail32
# (tail32.patch, on sg1), the tail levels' workgroups a warp too.
G=build-gpu/octrace-sg1; W=build-gpu/octrace-tail32
V=(--variant base= --variant sg1=BIN=$G --variant sg1b=BIN=build-gpu/octrace-sg1b --variant tail32=BIN=$W)
ab engine_probes $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_probes $S --scene .assets/balloon/scene.gltf --accel octree
same_image "engine sg1" "$B" "$G" $S --scene .assets/2CylinderEngine.glb --accel octree
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
