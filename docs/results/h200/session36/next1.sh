# Prepared in session 36 as run 11 and rehearsed (tools/gpu_dry_run.sh),
# never run: the H100 was not lent at 19:53, 20:05 and 20:06 UTC, and the
# failed calls left too little device time to start an H200. For the next
# session with a GPU, first. Pack: .gpub/bin.txz = 8f968ef (a4d762f's code)
# with session 34's topcost probe; if it is gone: tools/gpu_pack.sh
# topcost=docs/results/h200/session34/topcost_env.patch.
# a4d762f (log 123: the top level's binary BVH walk in
# while-while form where its leaves hold >= 4 references on average, on a
# GPU): the GPU suites; auto against `--bvh-walk one-loop` where the rule
# takes while-while (1M and 128,000 spheres, r = 0.1; 10M) and where it
# does not (1M at r = 0.01, 3.4 a leaf: the same pipeline, so within
# noise); the peer side by side (its scene keeps the one loop); `bench`
# of the goals' rows; the top level's node cost 3 and 4 with while-while
# at 1M. Expectations: expected.md ("run11.sh").
# Carried: .gl, .gpub, .assets, .peers.
source tools/gpu_run.sh
gpu_suites
V=(--variant "auto=" --variant "one=-- --bvh-walk one-loop")
AB_TIMEOUT=150 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
ab s128k_bvh $S --spheres 128000 --radius 0.1 --accel bvh
AB_TIMEOUT=150 ab s1m_r001_bvh $S --spheres 1000000 --radius 0.01 --accel bvh
AB_TIMEOUT=300 ab s10m_bvh $S --spheres 10000000 --radius 0.1 --accel bvh
# The top level's SAH node cost (session 34's topcost probe, in the pack as
# build-gpu/octrace-topcost) with the while-while walk: leaves fuller than
# the cost of 2 gives, now that a warp tests them together.
TC=build-gpu/octrace-topcost
V=(--variant "ww2=-- --bvh-walk while-while" --variant "ww3=BIN=$TC OCTRACE_BVH_TOPCOST=3 -- --bvh-walk while-while" --variant "ww4=BIN=$TC OCTRACE_BVH_TOPCOST=4 -- --bvh-walk while-while")
AB_TIMEOUT=150 ab s1m_topcost $S --spheres 1000000 --radius 0.1 --accel bvh
"$B" render $S --spheres 1000000 --radius 0.1 --accel bvh -q -o "$R/a.pfm"
"$B" render $S --spheres 1000000 --radius 0.1 --accel bvh --bvh-walk one-loop -q -o "$R/b.pfm"
cmp -s "$R/a.pfm" "$R/b.pfm" && echo "s1m auto = one-loop, identical" >> "$T" || echo "s1m auto vs one-loop DIFFERENT" >> "$T"
rm -f "$R/a.pfm" "$R/b.pfm"
peer_both
bench_goals
gpu_finish
