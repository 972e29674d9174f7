# Prepared in session 37 for the next session with a GPU, after next1.sh
# (the same pack). Expectations: expected.md ("next2.sh"). Carried: .gl,
# .gpub, .assets, .peers. About 7 minutes.
source tools/gpu_run.sh
# Log 125 at 10M (whole spheres against their visible parts, the BVH).
V=(--variant "keep=-- --hidden-parts keep" --variant "cull=")
AB_TIMEOUT=300 ab s10m_bvh $S --spheres 10000000 --radius 0.1 --accel bvh
# The peer side by side (its scene has no overlaps: as before), then
# bench's goal rows, and the octree at 10M (bench_goals has the BVH's).
peer_both
bench_goals
bench_logged spheres10m_octree 200 " ms" --accel octree --spheres 10000000 --radius 0.1
gpu_finish
