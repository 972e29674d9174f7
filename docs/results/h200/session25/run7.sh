# Session 25 on the H200, run 7 (expected.md): `--tail-depth 1` against
# the auto (2) on the meshes, both structures. Carried: .gl, .gpub (run 6's
# bin.txz: app/octrace = 3075a2e), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "auto=" --variant "d1=-- --tail-depth 1")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do for a in octree bvh; do
  AB_ROUNDS=5 AB_TIMEOUT=60 ab ${sc%%:*}_$a $S --scene ${sc#*:} --accel $a
done; done
gpu_finish
