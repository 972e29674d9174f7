# Log 42 on the H200: identity against 075c55a (the sphere scenes of
# tools/identity_check.sh and the two meshes at 10 spp), then the GPU suites.
# Carried: .gl, .gpub (bin.tgz: app/octrace and the three GPU test binaries
# of log 42, octrace-base of 075c55a), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base; B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for v in $A $B; do
  timeout 30 $v render --scene $sc --size 400x300 --spp 10 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "mesh identity $(basename $sc) 10 spp: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T; done
for v in $A $B; do timeout 30 $v render --spheres 488 --size 400x300 --spp 10 --device gpu -q --out /tmp/s_$(basename $v).pfm; done
echo "sphere identity 488 10 spp: $(cmp /tmp/s_octrace-base.pfm /tmp/s_octrace.pfm && echo bit-identical)" >> $T
DEVICE=gpu timeout 100 tools/identity_check.sh $A $B /tmp/id > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" >> $T
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 90 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_$t.txt | head -5 >> $T
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 300 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5 >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
