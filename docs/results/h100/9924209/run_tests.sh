set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >> $R/date.txt
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 100 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')"; grep "^\[  FAILED" $R/gpu_$t.txt | head -5
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 380 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')"; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
