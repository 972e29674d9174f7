# Session 49 run4 (a9d67a1: a subgroup a tile makes the lists; the auto by
# the sphere count, 16,384 on a GPU): the peer side by side (the auto on),
# `bench` of the sphere rows, the lists on against off over sphere counts
# past the auto's bound, render_test's camera-tile cases on the H100.
# Expectations in expected.md (run4).
source tools/gpu_run.sh
peer_both
bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
V=(--variant "off=-- --camera-tiles off" --variant "on=-- --camera-tiles on")
for n in 2000 8000 16000 32000; do ab s${n}_bvh $S --spheres $n --radius 0.1 --accel bvh; done
for n in 8000 16000; do ab s${n}_octree $S --spheres $n --radius 0.1 --accel octree; done
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
timeout 100 build-gpu/tests/render_test --gtest_filter='*CameraTiles*' > "$R/render_test.txt" 2>&1
echo "render_test camera tiles: ok $(grep -c '^\[       OK \]' "$R/render_test.txt"), failed $(grep -c '^\[  FAILED  \] .*(' "$R/render_test.txt") $(gtest_result "$R/render_test.txt")" >> "$T"
gpu_finish
