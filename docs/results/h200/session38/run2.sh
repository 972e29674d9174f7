# Session 38, run 2 (if the device time left allows: about 6 minutes, most
# of it a fresh machine's start): the octree against the BVH at 1M side by
# side at log 126, `bench`. The pack of run 1. Expected: the octree about
# 5.3 ms, the BVH about 4.2 (ratio about 1.27, from session 37's 1.65).
source tools/gpu_run.sh
bench_logged spheres1m 100 " ms" --accel octree,bvh --spheres 1000000 --radius 0.1
gpu_finish
