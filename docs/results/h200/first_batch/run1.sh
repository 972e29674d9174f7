# first_batch_lanes.patch on the H200: `render` A/B of 075c55a (base)
# against 075c55a + the patch (lanes), alternating, 5 rounds, device time;
# then the images: identity check and the two meshes, base against lanes.
# Carried: .gl, .gpub (bin.tgz: octrace-base, octrace-lanes, COMMIT), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base; B=build-gpu/octrace-lanes
$A devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base= --variant lanes=BIN=$B)
ab() { name=$1; shift; timeout 90 python3 tools/ab_render.py --octrace $A --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|lanes) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for v in $A $B; do
  timeout 30 $v render --scene $sc --size 400x300 --spp 10 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "mesh identity $(basename $sc) 10 spp: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace-lanes.pfm && echo bit-identical)" >> $T; done
DEVICE=gpu timeout 100 tools/identity_check.sh $A $B /tmp/id > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
