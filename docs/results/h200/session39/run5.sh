# Session 39 run5: log 130 (the materials in the render's precision only)
# against the code before it (octrace-base: both_materials.patch, every
# render uploading both forms), the whole process side by side at render's
# defaults on the dense fields, and the GPU suites at the session's last
# code (the hard cases run every precision; render_test's reconfigure and
# scene-hash cases switch precisions). Pack: tools/gpu_pack.sh
# base=docs/results/h200/session39/both_materials.patch. Carried: .gl,
# .gpub. Expectations in expected.md (run5).
source tools/gpu_run.sh
gpu_suites
export OCTRACE_TEST_DEVICE=gpu
timeout 200 build-gpu/tests/render_test --gtest_filter='*SceneHash*:*Reconfigure*:SurfaceCells*:*HiddenParts*' > "$R/render_test_more.txt" 2>&1
echo "render_test precision/reconfigure rc=$? $(gtest_result "$R/render_test_more.txt")" >> "$T"
V=(--variant base=BIN=$A --variant new=)
AB_METRIC=wall AB_TIMEOUT=150 ab wall_1m_10spp $S --spheres 1000000 --radius 0.1
AB_METRIC=wall AB_TIMEOUT=330 ab wall_10m_10spp $S --spheres 10000000 --radius 0.1
gpu_finish
