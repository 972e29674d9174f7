# Session 16 on the H200, run 5 (log 57): the octree's duplication budget
# (kMaxDuplication, 8 references per primitive along a path) on the meshes
# and the sphere fields, with the throwaway build octrace-sweep
# (octree_env.patch: OCTRACE_MAX_DUP; the default 8 is the code as it
# stands). `bench --warmup 0.5` (log 55).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
X=build-gpu/octrace-sweep
M=.assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
row() { grep -h '^| ' "$@" | grep -v 'scene |\|spheres |\|---' | cut -d'|' -f2,5,7,8,9,13,14,11 | tr -s ' ' | paste -sd';'; }
for d in 8 16 32; do
  for l in 10 4; do
    OCTRACE_MAX_DUP=$d timeout 60 $X bench --device gpu --accel octree --scene $M --octree-leaf $l \
      --csv "$R/meshes_d${d}_l$l.csv" > "$R/meshes_d${d}_l$l.log" 2>&1
    echo "dup $d leaf $l: $(row "$R/meshes_d${d}_l$l.log")" >> "$T"
  done
  OCTRACE_MAX_DUP=$d timeout 90 $X bench --device gpu --accel octree --spheres 488,8000,1000000 \
    --csv "$R/spheres_d$d.csv" > "$R/spheres_d$d.log" 2>&1
  echo "dup $d spheres: $(row "$R/spheres_d$d.log")" >> "$T"
done
timeout 60 $B bench --device gpu --accel bvh --scene $M > "$R/meshes_bvh.log" 2>&1
echo "bvh: $(row "$R/meshes_bvh.log")" >> "$T"
gpu_finish
