# Log 40 (476acad) on the H200: the identity check against 010c464, the GPU
# suites, the CUDA peer side by side and the sphere-count series.
# Carried: .gl, .gpub (bin.tgz: app/octrace and the three GPU test binaries
# of 476acad, octrace-base of 010c464), .assets, .peers.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
(cd .peers/karim && ./build.sh > $R/peer_build.txt 2>&1) &
DEVICE=gpu timeout 80 tools/identity_check.sh build-gpu/octrace-base $B /tmp/id > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" >> $T
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 80 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_$t.txt | head -5 >> $T
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 220 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5 >> $T
unset OCTRACE_TEST_DEVICE; wait
timeout 120 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer --rounds 5 > $R/peer.log 2>&1; echo "peer rc=$?" >> $T; tail -4 $R/peer/peer_compare.md >> $T
timeout 80 $B bench --device gpu --accel octree --spheres 488,8000,1000000,10000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1; echo "bench rc=$?" >> $T; tail -8 $R/spheres.log >> $T
rm -f $R/peer/*.ppm $R/peer/*.pfm $R/peer/*.png; tar czf $OUT/results.tgz -C /tmp res; cat $T
