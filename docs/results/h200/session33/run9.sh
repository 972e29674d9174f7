# Run 9 (14:07 UTC): the last part of session 30's run1.sh: session 29's shared-stack build at N = 0 against HEAD. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
X=build-gpu/octrace-sst
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant "head=" --variant "s0=BIN=$X OCTRACE_SSTACK=0")
ab peer_octree $P --accel octree
ab peer_bvh $P --accel bvh
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
gpu_finish
