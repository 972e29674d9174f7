# Log 41 (0eeca9d) on the H200: registers, A/B against 476acad and against
# the c740ecf form (octrace-old, run4.sh), the identity check against
# 476acad, then the GPU suites. Carried: .gl, .gpub (bin.tgz: app/octrace
# and the three GPU test binaries of 0eeca9d, octrace-base of 476acad,
# octrace-old), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
for sc in tools/scenes/peer_field.json .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do
  echo "regs $(basename $sc): $(timeout 30 $B render --scene $sc --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png 2>&1 | grep -E '^pipeline  Register' | tr -s ' ')" >> $T
done
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base=BIN=build-gpu/octrace-base --variant new= --variant old=BIN=build-gpu/octrace-old)
ab() { name=$1; shift; timeout 80 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|new|old) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab engine --scene .assets/2CylinderEngine.glb $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab s488 --spheres 488 --radius 0.1 $S
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for v in build-gpu/octrace-base $B; do
  timeout 30 $v render --scene $sc --size 400x300 --spp 4 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "mesh identity $(basename $sc): $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T; done
DEVICE=gpu timeout 80 tools/identity_check.sh build-gpu/octrace-base $B /tmp/id > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" >> $T
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 80 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_$t.txt | head -5 >> $T
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 220 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5 >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
