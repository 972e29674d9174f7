# Prepared in session 35 (its GPU time spent), for the next session with a
# GPU: the goals' rows at the session's last code (log 117's queue,
# ca148ff; the GPU suites ran at 3825c45 only): the GPU suites, the peer
# side by side with both structures, `bench`; the engine's octree at 12
# and 16 references a triangle. Expectations: expected.md
# ("next1.sh"). Carried: .gl, .gpub, .assets, .peers.
source tools/gpu_run.sh
gpu_suites
peer_both
bench_goals
# The engine's octree with a larger split budget (log 57: 16 references a
# triangle took it within 1.08x of the BVH then, at 81 bytes a triangle
# against issue 11's 48): how far from 2e9 rays/s the memory keeps it now.
V=(--variant "refs8=" --variant "refs12=-- --octree-refs 12" --variant "refs16=-- --octree-refs 16")
ab refs_engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
gpu_finish
