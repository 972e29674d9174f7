# Session 51, run 4: render_test's cases that run 1's 200 s cut off (the
# tail-queue case alone took 163 s there): the camera tiles' auto, the
# tiles kept while the camera stays, the dispatch times; a limit of 300 s.
# Pack: as run1. Carry .gl, .gpub, .assets. Expectations: expected.md, run4.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
timeout 300 build-gpu/tests/render_test --gtest_filter='*CameraTiles*:*DispatchTimes*:*TailQueue*:-*TailQueueDoesNotChangeTheResult:*CameraTilesChangeNoPixel' > "$R/render_test.txt" 2>&1
echo "render_test: ok $(grep -c '^\[       OK \]' "$R/render_test.txt"), failed $(grep -cE '^\[  FAILED  \] .* \([0-9]+ ms\)$' "$R/render_test.txt") $(gtest_result "$R/render_test.txt")" >> "$T"
cp "$R/render_test.txt" "$OUT/"
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
