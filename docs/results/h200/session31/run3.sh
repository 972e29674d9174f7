# Prepared in session 31 (no GPU lent there), for the next session with one:
# log 104, the four-wide BVH's child boxes quantised in the parent
# (q4.patch; build-gpu/octrace-q4 and its tests under build-gpu/tests/q4/),
# against HEAD with the same trees; its images against HEAD's; and its
# hard cases and accel_test on the GPU. Expectations:
# docs/results/lavapipe_20261205d/expected.md (written before the code).
# Carried: .gl, .gpub (bin.txz: COMMIT says which binary is which), .assets.
source tools/gpu_run.sh
Q=build-gpu/octrace-q4
V=(--variant "head=" --variant "q4=BIN=$Q")
ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
ab s1m_bvh4 $S --spheres 1000000 --radius 0.1 --accel bvh --bvh-width 4
ab s8000_bvh4 $S --spheres 8000 --radius 0.1 --accel bvh --bvh-width 4
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
ab peer_bvh4 $P --accel bvh --bvh-width 4
V=(--variant "head_binary=" --variant "q4_w4=BIN=$Q -- --bvh-width 4")
ab s1m_binary_vs_q4 $S --spheres 1000000 --radius 0.1 --accel bvh
same_image "engine bvh head/q4" $B $Q --size 600x400 --spp 4 --device gpu --scene .assets/2CylinderEngine.glb --accel bvh
same_image "balloon bvh head/q4" $B $Q --size 600x400 --spp 4 --device gpu --scene .assets/balloon/scene.gltf --accel bvh
same_image "peer bvh4 head/q4" $B $Q --size 600x400 --spp 4 --device gpu --scene tools/scenes/peer_field.json --accel bvh --bvh-width 4
$B render $S --scene .assets/2CylinderEngine.glb --accel bvh --pipeline-stats -q -o $R/x.pfm > $R/stats_head.txt 2>&1
$Q render $S --scene .assets/2CylinderEngine.glb --accel bvh --pipeline-stats -q -o $R/x.pfm > $R/stats_q4.txt 2>&1
mkdir -p $R/q4; export OCTRACE_TEST_DEVICE=gpu; mkdir -p build-gpu/tests/tmp
suite q4/accel_test 240
timeout 240 build-gpu/tests/q4/hardcases_test --gtest_filter='*bvh*' > $R/q4/hardcases_bvh.txt 2>&1
echo "q4 hardcases bvh rc=$? $(gtest_result $R/q4/hardcases_bvh.txt)" >> $T
gpu_finish
