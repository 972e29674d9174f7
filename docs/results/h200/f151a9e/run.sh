# Log 37's change (f151a9e) on the H200: the GPU accel suite, the mesh hard
# cases, effects auto == all, and octree against BVH on the meshes (bench).
# Carried: .gl, .gpub (bin.tgz: app/octrace of f151a9e, app/octrace-old of
# bc55933, the three GPU test binaries), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
( export OCTRACE_TEST_DEVICE=gpu
timeout 40 build-gpu/tests/accel_test > $R/gpu_accel_test.txt 2>&1; echo "accel rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_accel_test.txt | tr '\n' ' ')"
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu_meshes.tsv timeout 70 build-gpu/tests/hardcases_test --gtest_filter='*mesh*:*triangle*' > $R/gpu_hardcases_meshes.txt 2>&1; echo "hardcases (meshes) rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_meshes.txt | tr '\n' ' ')"
) | tee $R/summary.txt
timeout 60 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/bvh_meshes.csv > $R/bvh_meshes.log 2>&1; echo "bench rc=$?" | tee -a $R/summary.txt; tail -6 $R/bvh_meshes.log | tee -a $R/summary.txt
OCTRACE_TEST_DEVICE=gpu timeout 60 build-gpu/tests/effects_test > $R/gpu_effects_test.txt 2>&1; echo "effects rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_effects_test.txt | tr '\n' ' ')" | tee -a $R/summary.txt
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
