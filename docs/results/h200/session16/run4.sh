# Session 16 on the H200, run 4: the octree's leaf size and SAH node cost on
# the meshes (and the sparse sphere fields), a sweep with a throwaway build
# (octrace-sweep: octree_env.patch, kNodeCost read from OCTRACE_NODE_COST;
# the default 2 is the code as it stands). `bench --warmup 0.5` (log 55).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
X=build-gpu/octrace-sweep
M=.assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
timeout 60 $B bench --device gpu --accel bvh --scene $M --csv "$R/meshes_bvh.csv" > "$R/meshes_bvh.log" 2>&1
echo "bvh: $(grep -v '^|\|Device\|^$' "$R/meshes_bvh.log" | grep rays | tr -s ' ' | paste -sd';')" >> "$T"
for c in 2 1 0.5; do
  for l in 10 4 2; do
    OCTRACE_NODE_COST=$c timeout 60 $X bench --device gpu --accel octree --scene $M --octree-leaf $l \
      --csv "$R/meshes_c${c}_l$l.csv" > "$R/meshes_c${c}_l$l.log" 2>&1
    OCTRACE_NODE_COST=$c timeout 60 $X bench --device gpu --accel octree --spheres 488,8000 --octree-leaf $l \
      --csv "$R/spheres_c${c}_l$l.csv" > "$R/spheres_c${c}_l$l.log" 2>&1
    echo "cost $c leaf $l: $(grep -h '^| ' "$R/meshes_c${c}_l$l.log" "$R/spheres_c${c}_l$l.log" | grep -v 'scene |\|spheres |\|---' | cut -d'|' -f2,5,7,8,9,13,14,11 | tr -s ' ' | paste -sd';')" >> "$T"
  done
done
gpu_finish
