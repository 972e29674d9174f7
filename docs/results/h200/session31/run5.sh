# Prepared in session 31 (no GPU lent there), for the next session with one:
# log 107's probe, the BVH's leaf rule on the GPU (build-gpu/octrace-leaf
# reads OCTRACE_BVH_MAXLEAF, default 8, and OCTRACE_BVH_NODECOST, default
# 1.0). Expectations: docs/results/lavapipe_20261205d/expected.md (log 107).
# Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
L=build-gpu/octrace-leaf
V=(--variant "base=" --variant "leaf1=OCTRACE_BVH_MAXLEAF=1" --variant "leaf2=OCTRACE_BVH_MAXLEAF=2"
   --variant "leaf4=OCTRACE_BVH_MAXLEAF=4" --variant "cost05=OCTRACE_BVH_NODECOST=0.5" --variant "cost2=OCTRACE_BVH_NODECOST=2")
B=$L
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
AB_TIMEOUT=150 ab peer_bvh $P --accel bvh
AB_TIMEOUT=150 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=150 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
AB_TIMEOUT=150 ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
AB_TIMEOUT=150 ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
gpu_finish
