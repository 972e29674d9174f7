# Session 39 run2: log 127's rule for --octree-surfaces auto (on a GPU only
# from 576M samples a render) against the rule before (on for every GPU
# render), the whole process side by side, and the suites that check it on
# the GPU. Pack: tools/gpu_pack.sh base=docs/results/h200/session39/old_rule.patch
# (octrace-base: this commit with the renderer's rule as before).
# Carried: .gl, .gpub. Expectations in expected.md (run2), written before.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
timeout 200 build-gpu/tests/render_test --gtest_filter='SurfaceCells*:*HiddenParts*:*TreeSettings*' > "$R/render_test_rule.txt" 2>&1
echo "render_test rule rc=$? $(gtest_result "$R/render_test_rule.txt")" >> "$T"
timeout 300 build-gpu/tests/accel_test > "$R/accel_test.txt" 2>&1
echo "accel_test rc=$? $(gtest_result "$R/accel_test.txt")" >> "$T"
for b in base new; do
  bin=$B; [ $b = base ] && bin=$A
  "$bin" render $S --spheres 1000000 --radius 0.1 --json -q -o "$R/$b.png" > "$R/render_1m_$b.json" 2>&1
  echo "$b 1M 10spp: $(python3 -c "import json;d=json.load(open('$R/render_1m_$b.json'));print('surface_cells',d['hidden_parts']['surface_cells'],'build',round(d['times_ms']['accel_build']),'render',round(d['times_ms']['render'],2))")" >> "$T"
done
V=(--variant base=BIN=$A --variant new=)
AB_METRIC=wall AB_TIMEOUT=150 ab wall_1m_10spp $S --spheres 1000000 --radius 0.1
AB_METRIC=accel_build AB_TIMEOUT=150 ab build_1m_10spp $S --spheres 1000000 --radius 0.1
AB_METRIC=wall AB_TIMEOUT=200 ab wall_1m_1000spp --size 1200x800 --spp 1000 --depth 50 --device gpu --spheres 1000000 --radius 0.1
AB_METRIC=wall AB_TIMEOUT=330 ab wall_10m_10spp $S --spheres 10000000 --radius 0.1
gpu_finish
