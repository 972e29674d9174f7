# Session 49 run5: `bench` of the goals' sphere rows at the camera tiles'
# final auto (the BVH up to 4,096 spheres, the octree up to 8,192).
# Expectations in expected.md (run5).
source tools/gpu_run.sh
bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
gpu_finish
