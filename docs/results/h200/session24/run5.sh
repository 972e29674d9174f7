# Session 24 on the H200, run 5 (expected.md): the meshes' tree
# parameters: octree leaf sizes and refs (flags), the BVH's SAH node cost
# (throwaway OCTRACE_BVH_NODE_COST, vcost.patch). Carried: .gl, .gpub
# (bin.txz: app/octrace = d354eca + vcost.patch, octrace-base =
# d354eca), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  V=(--variant "base=" --variant "leaf4=-- --octree-leaf 4" --variant "leaf6=-- --octree-leaf 6" --variant "leaf16=-- --octree-leaf 16" --variant "refs16=-- --octree-refs 16")
  AB_TIMEOUT=150 ab ${sc%%:*}_octree $S --scene ${sc#*:} --accel octree
  V=(--variant "base=" --variant "c025=OCTRACE_BVH_NODE_COST=0.25" --variant "c05=OCTRACE_BVH_NODE_COST=0.5" --variant "c2=OCTRACE_BVH_NODE_COST=2")
  AB_TIMEOUT=150 ab ${sc%%:*}_bvh $S --scene ${sc#*:} --accel bvh
done
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do
  for f in "" "--octree-leaf 6" "--octree-refs 16"; do
    echo "$sc $f: $($B render $S --scene $sc --accel octree $f --json -q -o $R/x.png | python3 -c 'import json,sys; j=json.load(sys.stdin); print(j["octree"]["bytes_per_primitive"], "bytes/primitive")')" >> $T
  done
done
rm -f $R/x.png
gpu_finish
