# Session 24 on the H200, run 6 (expected.md): --sample-lanes on the
# meshes and the peer's scene, both structures, 5 rounds. Carried: .gl,
# .gpub (bin.txz: app/octrace = 22020f6, octrace-base = the same), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
for a in octree bvh; do
  V=(--variant "auto=" --variant "l1=-- --sample-lanes 1" --variant "l2=-- --sample-lanes 2" --variant "l4=-- --sample-lanes 4")
  AB_TIMEOUT=120 ab engine_$a $S --scene .assets/2CylinderEngine.glb --accel $a
  AB_TIMEOUT=120 ab balloon_$a $S --scene .assets/balloon/scene.gltf --accel $a
  V=(--variant "auto=" --variant "l1=-- --sample-lanes 1" --variant "l2=-- --sample-lanes 2" --variant "l8=-- --sample-lanes 8")
  AB_TIMEOUT=150 ab peer_$a $P --accel $a
done
gpu_finish
