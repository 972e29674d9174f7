set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt
(
export OCTRACE_TEST_DEVICE=gpu
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 330 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')"; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5
for t in effects_test texture_test render_test golden_test; do
  timeout 100 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')"; grep "^\[  FAILED" $R/gpu_$t.txt | head -3
done
)
OCTRACE_EXPERIMENT_NO_CONTRACTION=1 NEW_FLAGS="--nee off" DEVICE=gpu timeout 90 tools/identity_check.sh build-gpu/app/octrace-48791cc $B /tmp/idc > $R/identity_vs_48791cc_nocontract.txt 2>&1; tail -1 $R/identity_vs_48791cc_nocontract.txt
find /tmp/res -name "*.png" -size +200k -delete; find /tmp/res -name "*.pfm" -delete; find /tmp/res -name "*.accum" -delete; tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
