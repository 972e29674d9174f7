# Session 20 on the H200, run 4 (expected.md): --tail-depth 2/3/4(/5) over
# the goals' scenes with both structures; the peer's scene at depth 1 with
# the whole paths against the staged passes.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "t2=" --variant "t3=-- --tail-depth 3" --variant "t4=-- --tail-depth 4")
for a in bvh octree; do
  AB_TIMEOUT=120 ab s488_$a $S --spheres 488 --radius 0.1 --accel $a
  AB_TIMEOUT=120 ab balloon_$a $S --scene .assets/balloon/scene.gltf --accel $a
  AB_TIMEOUT=120 ab engine_$a $S --scene .assets/2CylinderEngine.glb --accel $a
done
AB_TIMEOUT=120 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
V=(--variant "t2=" --variant "t3=-- --tail-depth 3" --variant "t4=-- --tail-depth 4" --variant "t5=-- --tail-depth 5")
AB_TIMEOUT=150 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
V=(--variant "auto=" --variant "whole=-- --tail-depth off")
P1="--scene tools/scenes/peer_field.json --depth 1 --rr-depth 1 --device gpu --size 1920x1080 --spp 64 --accel bvh"
ab peer_d1 $P1
gpu_finish
