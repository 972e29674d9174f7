# Session 16 on the H200, run 6 (log 57): `--octree-refs` as built (the split
# budget as OctreeParams::max_refs), accel_test with its new variant (the
# octree at 32 references per primitive against brute force), and `bench`
# of the meshes at 8 (the default), 16 and 32 beside the BVH.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
suite accel_test 150
M=.assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
row() { grep -h '^| ' "$@" | grep -v 'scene |\|---' | cut -d'|' -f2,5,7,8,9,11,13,14 | tr -s ' ' | paste -sd';'; }
timeout 60 $B bench --device gpu --accel bvh --scene $M --csv "$R/meshes_bvh.csv" > "$R/meshes_bvh.log" 2>&1
echo "bvh: $(row "$R/meshes_bvh.log")" >> "$T"
for r in 8 16 32; do
  timeout 60 $B bench --device gpu --accel octree --scene $M --octree-refs $r --csv "$R/meshes_refs$r.csv" \
    > "$R/meshes_refs$r.log" 2>&1
  echo "octree-refs $r: $(row "$R/meshes_refs$r.log")" >> "$T"
done
gpu_finish
