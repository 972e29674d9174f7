# Prepared in session 33: the octree's leaf size over spheres on the GPU
# again (log 30 measured leaf 4 at 9924209, before octant culling's later
# forms, the tail queue, logs 62-65: -0.9% on the peer's scene, -2.6% at
# 488 spheres; log 110 made the leaf size an auto setting per device).
# With them the octant culling off (on for every GPU since log 29; log 110's
# leaf 16 with it off won on Mesa 25's lavapipe). Flags only: HEAD's binary. Expectations: expected.md. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
V=(--variant "auto=" --variant "leaf4=-- --octree-leaf 4" --variant "leaf6=-- --octree-leaf 6" --variant "leaf16=-- --octree-leaf 16"
   --variant "cull_off=-- --octant-culling off" --variant "cull_off16=-- --octant-culling off --octree-leaf 16")
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
AB_TIMEOUT=150 ab peer_octree $P --accel octree
AB_TIMEOUT=100 ab s488_octree $S --spheres 488 --radius 0.1 --accel octree
AB_TIMEOUT=100 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=150 ab s1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
gpu_finish
