# Session 51, run 1 (prepared in session 50 as next1.sh, which no device
# time was left to run). Pack: tools/gpu_pack.sh
# before=docs/results/h200/session51/before_146_147.patch (HEAD, 544d289,
# without logs 146 and 147: the list pass before every batch, the empty
# subgroup dispatches; made again on 544d289, where session 50's patch no
# longer applied) as build-gpu/octrace-before. Carry .gl, .gpub and
# .assets (not .peers: with it the tree passes the 64 MiB a call may
# carry). Expectations: docs/results/h200/session51/expected.md. The hard
# cases moved to run3.sh (a call's 600 s).
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant before=BIN=build-gpu/octrace-before --variant head=)
ab peer_146 $PEER --accel bvh
ab engine_147 $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_147 $S --scene .assets/balloon/scene.gltf --accel octree
same_image "peer 146" build-gpu/octrace-before "$B" $PEER --accel bvh
same_image "engine 147" build-gpu/octrace-before "$B" $S --scene .assets/2CylinderEngine.glb --accel octree
timeout 200 build-gpu/tests/render_test --gtest_filter='*CameraTiles*:*DispatchTimes*:*TailQueue*' > "$R/render_test.txt" 2>&1
echo "render_test: ok $(grep -c '^\[       OK \]' "$R/render_test.txt"), failed $(grep -cE '^\[  FAILED  \] .* \([0-9]+ ms\)$' "$R/render_test.txt") $(gtest_result "$R/render_test.txt")" >> "$T"
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
