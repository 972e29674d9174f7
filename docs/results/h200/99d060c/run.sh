# Optimisation log 39 on the H200: the big list as the octree walk's first
# leaf (99d060c) against 527bfd1 (A/B alternating, 5 rounds, device time),
# registers, the identity check, then the GPU suites. summary.txt is written
# into $OUT as it goes. Carried: .gl, .gpub (bin.tgz: 99d060c's app/octrace
# and GPU test binaries, octrace-base of 527bfd1), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace; A=build-gpu/octrace-base
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=$OUT/res; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V="--variant base= --variant bigleaf=BIN=$B"
ab() { name=$1; shift; timeout 45 python3 tools/ab_render.py --octrace $A --rounds 5 --render "$*" $V --out /tmp/ab_$name.md > /tmp/ab_$name.log 2>&1; echo "$name: $(grep -E '^\| (base|bigleaf)' /tmp/ab_$name.md | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab s488 --spheres 488 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab pbr_field --scene tools/scenes/pbr_field.json $S
for v in $A $B; do for sc in tools/scenes/peer_field.json .assets/2CylinderEngine.glb; do
  echo "regs $(basename $v) $(basename $sc): $(timeout 20 $v render --scene $sc --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png 2>&1 | grep -E '^pipeline  Register' | tr -s ' ')" >> $T
done; done
DEVICE=gpu timeout 70 tools/identity_check.sh $A $B /tmp/id > /tmp/identity.txt 2>&1; echo "identity rc=$? $(tail -1 /tmp/identity.txt)" >> $T
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 70 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_$t.txt | head -5 >> $T
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 200 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5 >> $T
tar czf $OUT/ab.tgz -C /tmp $(cd /tmp && ls ab_*.md ab_*.log identity.txt); cat $T
