# Session 35, run 6: the tail queue's entries (a probe,
# tail_queue_env.patch: OCTRACE_TAIL_QUEUE sets them). Run 5 took 8,000
# spheres at 16 samples (1200x800) in 2.07x the time of 10 with the BVH
# (1.99x with the octree): the queue holds 2.8M paths (its 256 MiB
# budget), 29% of 10 samples' paths and 18% of 16's; a head whose path
# finds the queue full finishes it itself. The peer's scene (8 samples of
# 1920x1080 a dispatch) has the same 2.8M, 17%. Expectations: expected.md.
# Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
S16="--size 1200x800 --spp 16 --depth 50 --device gpu"
C=build-gpu/octrace-tailqueue
V=(--variant "auto=" --variant "q4m=BIN=$C OCTRACE_TAIL_QUEUE=4150000" --variant "q6m=BIN=$C OCTRACE_TAIL_QUEUE=6000000"
   --variant "q8m=BIN=$C OCTRACE_TAIL_QUEUE=8300000")
AB_TIMEOUT=120 ab q_peer_bvh $P --accel bvh
AB_TIMEOUT=120 ab q_peer_octree $P --accel octree
V=(--variant "auto=" --variant "q4m=BIN=$C OCTRACE_TAIL_QUEUE=3840000" --variant "q8m=BIN=$C OCTRACE_TAIL_QUEUE=7700000")
ab q16_s8000_bvh $S16 --spheres 8000 --radius 0.1 --accel bvh
ab q16_s8000_octree $S16 --spheres 8000 --radius 0.1 --accel octree
ab q16_s488_bvh $S16 --spheres 488 --radius 0.1 --accel bvh
ab q10_s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=120 ab q10_s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
ab q10_engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
ab q10_balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
gpu_finish
