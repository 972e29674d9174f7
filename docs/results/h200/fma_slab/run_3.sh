# Optimisation log 35/36, third run: the registers of the three builds of
# run_ab2.sh (render --pipeline-stats), and the ahead-of-driver test on the
# GPU before (b4ce7df) and after the re-decoration of the optimised module.
# Carried: .gl, .gpub (ab3.tgz), .assets.
set -u; mkdir -p /tmp/v; tar xzf .gpub/ab3.tgz -C /tmp/v
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=/tmp/v/octrace-base
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat /tmp/v/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
for v in base fma fma2; do
  for sc in "peer|--scene tools/scenes/peer_field.json --rr-depth 1" "s1m|--spheres 1000000 --radius 0.1" "engine|--scene .assets/2CylinderEngine.glb"; do
    n=${sc%%|*}; f=${sc#*|}
    echo "== $v $n"; timeout 60 /tmp/v/octrace-$v render $f --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/o.png 2>&1 | grep -v '^\s*$' | tail -12
  done
done > $R/pipeline_stats.txt 2>&1
grep -i 'regist\|==' $R/pipeline_stats.txt | head -40
export OCTRACE_TEST_DEVICE=gpu
timeout 60 /tmp/v/effects_test-base --gtest_filter='AheadOfDriver*' > $R/gpu_effects_base_ahead.txt 2>&1; echo "base ahead rc=$? $(grep -E '^\[  (PASSED|FAILED)|differ' $R/gpu_effects_base_ahead.txt | tr '\n' ' ')"
timeout 150 /tmp/v/effects_test-fix > $R/gpu_effects_test.txt 2>&1; echo "fix effects rc=$? $(grep -E '^\[  (PASSED|FAILED)|differ' $R/gpu_effects_test.txt | tr '\n' ' ')"
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
