# Prepared in session 37 for the next session with a GPU, after next1.sh
# (the same pack). Expectations: expected.md ("next2.sh"). Carried: .gl,
# .gpub, .assets, .peers. About 7 minutes.
source tools/gpu_run.sh
# Log 125 at 10M (whole spheres against their visible parts, the BVH).
V=(--variant "keep=-- --hidden-parts keep" --variant "cull=")
AB_TIMEOUT=300 ab s10m_bvh $S --spheres 10000000 --radius 0.1 --accel bvh
# The two images at 10M: on lavapipe 15 of 6,000 pixels differed at depth
# 50 (none at depth 8); our reading is llvmpipe's limit of 65,535 loop
# iterations an invocation, which the whole spheres' hundreds of tests a
# query reach on a long path. A GPU has no such limit: identical expected.
"$B" render --size 400x240 --spp 2 --depth 50 --device gpu --spheres 10000000 --radius 0.1 --accel bvh --hidden-parts keep -q -o "$R/a.pfm"
"$B" render --size 400x240 --spp 2 --depth 50 --device gpu --spheres 10000000 --radius 0.1 --accel bvh -q -o "$R/b.pfm"
cmp -s "$R/a.pfm" "$R/b.pfm" && echo "s10m keep = cull, identical" >> "$T" || echo "s10m keep vs cull DIFFERENT" >> "$T"
rm -f "$R/a.pfm" "$R/b.pfm"
# The peer side by side (its scene has no overlaps: as before), then
# bench's goal rows, and the octree at 10M (bench_goals has the BVH's).
peer_both
bench_goals
bench_logged spheres10m_octree 200 " ms" --accel octree --spheres 10000000 --radius 0.1
gpu_finish
