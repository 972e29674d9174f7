# Session 24 on the H200, run 2 (expected.md): --instancing auto (the
# new default) and keep against HEAD on the engine, both structures; bench
# of the meshes; the GPU suites and render_test's instancing case with the
# new code. Carried: .gl, .gpub (bin.txz: app/octrace, tests,
# octrace-base), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "auto=" --variant "keep=-- --instancing keep")
for a in octree bvh; do
  AB_ROUNDS=7 AB_TIMEOUT=150 ab engine_$a $S --scene .assets/2CylinderEngine.glb --accel $a
done
gpu_suites
OCTRACE_TEST_DEVICE=gpu timeout 120 build-gpu/tests/render_test --gtest_filter='*InstancesRenderAsCopies*' > $R/render_test_instances.txt 2>&1
echo "render_test instances rc=$? $(gtest_result $R/render_test_instances.txt)" >> $T
timeout 150 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $R/bench_meshes.txt 2>&1
echo "bench meshes rc=$?" >> $T; grep -E '^\|' $R/bench_meshes.txt | tail -5 >> $T
gpu_finish
