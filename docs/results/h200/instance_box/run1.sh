# Log 48 on the H200: `render` A/B against 6ebd4af (5 rounds, device time)
# on the meshes (octree and BVH) and a sphere field; identity; the GPU
# suites with the change. Carried: .gl, .gpub (bin.tgz: app/octrace and the
# GPU test binaries with the change, octrace-base of f169de2 = 6ebd4af's
# code, COMMIT), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base; B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base=BIN=$A --variant log48=)
ab() { name=$1; shift; timeout 60 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|log48) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab balloon_bvh --scene .assets/balloon/scene.gltf $S --accel bvh
ab engine_bvh --scene .assets/2CylinderEngine.glb $S --accel bvh
ab s488 --spheres 488 --radius 0.1 $S
for v in $A $B; do echo "regs $(basename $v) engine: $(timeout 30 $v render --scene .assets/2CylinderEngine.glb --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png 2>&1 | grep -E '^pipeline  Register' | tr -s ' ')" >> $T; done
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for acc in octree bvh; do for v in $A $B; do
  timeout 30 $v render --scene $sc --size 400x300 --spp 10 --accel $acc --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "mesh identity $(basename $sc) $acc 10 spp: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T; done; done
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 90 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_$t.txt | head -5 >> $T
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 280 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')" >> $T; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5 >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
