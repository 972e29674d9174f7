# Session 42 run3: the GPU suites at e3ddf1d (the copy leaves as the GPU's
# auto for meshes): the hard cases in four shards, accel_test, render_test's
# tail-queue cases, and render_test's tree-settings cases on the GPU.
# Pack: run2's. Carried: .gl, .gpub, .assets. Expectations in expected.md (run2).
source tools/gpu_run.sh
gpu_suites
export OCTRACE_TEST_DEVICE=gpu
timeout 200 build-gpu/tests/render_test --gtest_filter='*TreeSettings*:OctreeLeaf.*:OctreeRefs.*' > "$R/render_test_autos.txt" 2>&1
echo "render_test autos rc=$? $(gtest_result "$R/render_test_autos.txt")" >> "$T"
gpu_finish
