# Session 45 run2: the GPU run scripts' tools after this session's changes
# to them (8ea7d81: tool_args in every script), on good input where they
# run: make_grid_glb.py and ab_render.py (mesh_ab: two variants of the same
# binary, 2 rounds), peer/compare.py (the peer built, then side by side
# with the BVH) and walk_stats.py (the peer's scene). Pack: run1's
# (9615e25). Carried: .gl, .gpub, .assets, .peers/karim. Expectations in
# expected.md (run2).
source tools/gpu_run.sh
V=(--variant a= --variant b=)
AB_ROUNDS=2 mesh_ab
peer_build
peer peer_bvh --accel bvh
timeout 120 python3 tools/walk_stats.py --octrace "$B" --accel octree,bvh --render "--device gpu --size 1200x800 --spp 2" \
  --scene "peer=--scene tools/scenes/peer_field.json" --out "$R/walk.md" > "$R/walk.log" 2>&1
echo "walk_stats rc=$?: $(grep -c '^| peer' "$R/walk.md" 2>/dev/null) rows" >> "$T"
gpu_finish
