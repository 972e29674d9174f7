# Session 38, run 2: after run 1 (the same pack): `bench` of the goals'
# sphere rows at log 126 (the octree and the BVH at 488 / 8,000 / 1M), and
# the octree at 10M before and after (bench warms up first, log 55).
# Expectations: expected.md. Carried: .gl, .gpub. About 7 minutes.
source tools/gpu_run.sh
bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
B=$A bench_logged spheres10m_octree_base 170 " ms" --accel octree --spheres 10000000 --radius 0.1
bench_logged spheres10m_octree 170 " ms" --accel octree --spheres 10000000 --radius 0.1
gpu_finish
