# The hard-case suite again on run5.sh's binaries (0eeca9d): run5's 220 s
# limit cut it off after 361 of 402 cases, none failed (that run's host took
# 1.3-2x longer over every test than run2's, brute force included).
# Carried: .gl, .gpub (bin.tgz of run5.sh).
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
T=$OUT/summary.txt; { date -u; cat build-gpu/COMMIT; nproc; } > $T
OCTRACE_TEST_DEVICE=gpu OCTRACE_HARDCASES_TABLE=$OUT/hardcases_gpu.tsv timeout 420 build-gpu/tests/hardcases_test > $OUT/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)|tests from .* ran' $OUT/gpu_hardcases_test.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $OUT/gpu_hardcases_test.txt | head -5 >> $T; cat $T
