# The GPU suites at f169de2 (--walk-stats) on the H200: accel_test,
# effects_test and the hard cases, on the NVIDIA driver.
# Carried: .gl, .gpub (bin.tgz as run1.sh), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 90 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_$t.txt | head -5 >> $T
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 300 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5 >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
