# Prepared in session 34 (its GPU time spent), for the next session with a
# GPU: the settings tuned before logs 114 and 115 gave the pipeline 47
# registers and the GPU's sphere octrees leaves of 24, measured again with
# them (flags only, HEAD's app/octrace): the sample lanes (auto 4 over
# spheres) and the octree's leaf around 24. Expectations: expected.md
# beside this script. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant "auto=" --variant "lanes1=-- --sample-lanes 1" --variant "lanes2=-- --sample-lanes 2" --variant "lanes8=-- --sample-lanes 8")
AB_TIMEOUT=120 ab lanes_peer_octree $P --accel octree
AB_TIMEOUT=120 ab lanes_peer_bvh $P --accel bvh
AB_TIMEOUT=60 ab lanes_s488_octree $S --spheres 488 --radius 0.1 --accel octree
AB_TIMEOUT=60 ab lanes_s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=120 ab lanes_s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
AB_TIMEOUT=90 ab lanes_engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
V=(--variant "auto=" --variant "leaf16=-- --octree-leaf 16" --variant "leaf20=-- --octree-leaf 20" --variant "leaf28=-- --octree-leaf 28")
AB_TIMEOUT=120 ab leaf_peer_octree $P --accel octree
AB_TIMEOUT=60 ab leaf_s488_octree $S --spheres 488 --radius 0.1 --accel octree
AB_TIMEOUT=60 ab leaf_s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=60 ab leaf_s2000_octree $S --spheres 2000 --radius 0.1 --accel octree
gpu_finish
