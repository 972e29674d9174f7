# Session 24 on the H200, run 4 (expected.md): the kept code: GPU suites,
# render_test's instancing cases, bench of the meshes, spheres against
# c66d2c9. Carried: .gl, .gpub (bin.txz: app/octrace, tests, octrace-base
# = c66d2c9), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
gpu_suites
OCTRACE_TEST_DEVICE=gpu timeout 120 build-gpu/tests/render_test --gtest_filter='*InstancesRenderAsCopies*:*OneInstance*' > $R/render_test_instances.txt 2>&1
echo "render_test instances rc=$? $(gtest_result $R/render_test_instances.txt)" >> $T
timeout 150 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $R/bench_meshes.txt 2>&1
echo "bench meshes rc=$?" >> $T; grep -E '^\|' $R/bench_meshes.txt | tail -5 >> $T
V=(--variant "base=BIN=$A" --variant "new=")
for a in octree bvh; do
  ab spheres8000_$a $S --spheres 8000 --radius 0.1 --accel $a
  ab peer_$a --scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64 --accel $a
done
gpu_finish
