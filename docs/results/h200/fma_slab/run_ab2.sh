# Optimisation log 35, second run: the multiply-add slab test with one margin
# for all axes (fma, run_ab.sh) and with a margin per axis folded into the
# offsets (fma2), against base (b4ce7df), H200 A/B alternating, 5 rounds,
# device time; then the image identity check and the GPU test suites on fma2.
# Carried: .gl, .gpub (ab2.tgz: three binaries and the fma2 test binaries), .assets.
set -u; mkdir -p /tmp/v; tar xzf .gpub/ab2.tgz -C /tmp/v
mkdir -p build-gpu/app build-gpu/tests; cp /tmp/v/octrace-fma2 build-gpu/app/octrace; cp /tmp/v/tests/* build-gpu/tests/
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=/tmp/v/octrace-base
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat /tmp/v/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V="--variant base= --variant fma=BIN=/tmp/v/octrace-fma --variant fma2=BIN=/tmp/v/octrace-fma2"
ab() { name=$1; shift; timeout 80 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" $V --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name: $(tail -3 $R/ab_$name.md | cut -d'|' -f2,5,9 | tr '\n' ' ')"; }
{
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab peer_bvh --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu --accel bvh
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab s1m --spheres 1000000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
} | tee $R/summary.txt
DEVICE=gpu timeout 90 tools/identity_check.sh $B /tmp/v/octrace-fma2 /tmp/idw > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" | tee -a $R/summary.txt
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 80 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')"; grep "^\[  FAILED" $R/gpu_$t.txt | head -5
done | tee -a $R/summary.txt
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 230 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')" | tee -a $R/summary.txt; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
