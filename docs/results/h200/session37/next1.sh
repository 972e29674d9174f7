# Prepared in session 37 (no GPU was lent to it) for the next session with
# one, first. Pack: tools/gpu_pack.sh at the commit this file names in
# README.txt (log 125: the parts of spheres inside opaque spheres left out
# of the trees). Expectations: expected.md ("next1.sh"). Carried: .gl,
# .gpub, .assets, .peers. About 6 minutes; next2.sh (the 10M A/B, the
# peer, bench) after it.
source tools/gpu_run.sh
# The GPU suites at this code (the hard cases with dense_overlapping_field,
# accel_test with dense_overlapping and camera_in_an_opaque_sphere against
# brute force, render_test's tail-queue cases) and render_test's
# hidden-parts case.
gpu_suites
suite_logged "$R/render_hidden.txt" build-gpu/tests/render_test --gtest_filter='*HiddenParts*'
echo "render_test hidden parts: $(gtest_result "$R/render_hidden.txt")" >> "$T"
# Log 125 on the GPU: whole spheres (keep) against their visible parts
# (cull, the default) where spheres overlap (1M and 10M at r = 0.1), and
# where none do (8,000 at r = 0.1: the same trees, so within noise).
V=(--variant "keep=-- --hidden-parts keep" --variant "cull=")
AB_TIMEOUT=150 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
AB_TIMEOUT=150 ab s1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
"$B" render $S --spheres 1000000 --radius 0.1 --accel bvh --hidden-parts keep -q -o "$R/a.pfm"
"$B" render $S --spheres 1000000 --radius 0.1 --accel bvh -q -o "$R/b.pfm"
cmp -s "$R/a.pfm" "$R/b.pfm" && echo "s1m keep = cull, identical" >> "$T" || echo "s1m keep vs cull DIFFERENT" >> "$T"
rm -f "$R/a.pfm" "$R/b.pfm"
# Log 123's rule (while-while where the top level's leaves hold >= 4
# references on average) against its other form at 1M, now that the
# leaves hold columns: the rule's choice is in render --json.
"$B" render $S --spheres 1000000 --radius 0.1 --accel bvh --json -q -o "$R/c.pfm" | python3 -c "import json,sys; j=json.load(sys.stdin); print('s1m walk:', j['bvh']['top_walk'], 'refs/leaf %.2f' % j['bvh']['top_refs_per_leaf'], 'hidden', j['hidden_parts'])" >> "$T"
rm -f "$R/c.pfm"
V=(--variant "one=-- --bvh-walk one-loop" --variant "ww=-- --bvh-walk while-while")
AB_TIMEOUT=150 ab s1m_walk $S --spheres 1000000 --radius 0.1 --accel bvh
gpu_finish
