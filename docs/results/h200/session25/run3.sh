# Session 25 on the H200, run 3 (expected.md): the meshes' tree parameters
# after log 72. Carried: .gl, .gpub (bin.txz: app/octrace = aba39a2,
# var/cost = aba39a2 + vcost2.patch), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
C=build-gpu/var/cost
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  V=(--variant "base=" --variant "leaf8=-- --octree-leaf 8" --variant "leaf14=-- --octree-leaf 14" --variant "node4=BIN=$C OCTRACE_OCTREE_NODE_COST=4")
  AB_ROUNDS=7 AB_TIMEOUT=200 ab ${sc%%:*}_octree $S --scene ${sc#*:} --accel octree
  V=(--variant "base=" --variant "c2=BIN=$C OCTRACE_BVH_NODE_COST=2" --variant "c05=BIN=$C OCTRACE_BVH_NODE_COST=0.5")
  AB_ROUNDS=7 AB_TIMEOUT=160 ab ${sc%%:*}_bvh $S --scene ${sc#*:} --accel bvh
done
gpu_finish
