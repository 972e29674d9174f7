# Session 39 run1: session 38's next1.sh as it was, at 35a27ec's pack.
# Prepared in session 38 for the next session with a GPU (its device time
# ran out after run1): the octree against the BVH side by side at log 126
# (the goals' sphere rows, the meshes, 10M with both structures), the GPU
# suites, and the peer. Pack: tools/gpu_pack.sh at the commit to measure.
# Carried: .gl, .gpub, .assets, .peers. About 8 minutes.
# Expected: 488 / 8,000 as session 37 within 2% (log 126 leaves their
# trees alone); the octree at 1M about 5.3 ms, the BVH about 4.2 (ratio
# about 1.27, from 1.65); at 10M the octree about 8.2 ms, the BVH about 6.3
# (about 1.3, from 4.70); the balloon and the engine as session 37.
source tools/gpu_run.sh
gpu_suites
bench_goals
bench_logged spheres10m_octree 200 " ms" --accel octree --spheres 10000000 --radius 0.1
peer_both
gpu_finish
