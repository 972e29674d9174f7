# Session 25 on the H200, run 4 (expected.md): `bench` of the meshes with
# the kept code (cd9c403, log 72) and with c982fe1, and the GPU suites with
# the kept code. Carried: .gl, .gpub (bin.txz: app/octrace and tests =
# cd9c403, octrace-base = c982fe1), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
M="--device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb"
timeout 150 $B bench $M > $OUT/bench_meshes.txt 2>&1; echo "bench cd9c403 rc=$?" >> $T; grep -E "rays/s$" $OUT/bench_meshes.txt >> $T
timeout 150 $A bench $M > $OUT/bench_meshes_c982fe1.txt 2>&1; echo "bench c982fe1 rc=$?" >> $T; grep -E "rays/s$" $OUT/bench_meshes_c982fe1.txt >> $T
gpu_suites
OCTRACE_TEST_DEVICE=gpu timeout 100 build-gpu/tests/render_test --gtest_filter='*InstancesRenderAsCopies*:*OneInstance*:*Lanes*' > $R/render_test_instances.txt 2>&1
echo "render_test instances and lanes rc=$? $(gtest_result $R/render_test_instances.txt)" >> $T
gpu_finish
