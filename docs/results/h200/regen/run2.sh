# Two more codings on the H200 after run1: nobar (each lane traces up to 8
# samples whole, one barrier pair per 8 rounds) and regen2 (regeneration with
# one call site each for path_begin and path_step). Registers, then `render`
# A/B against a70c188 (5 rounds, device time). Carried: .gl, .gpub, .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base
$A devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
for v in nobar regen2; do for sc in tools/scenes/peer_field.json .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do
  echo "regs $v $(basename $sc): $(timeout 30 build-gpu/octrace-$v render --scene $sc --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png 2>&1 | grep -E '^pipeline  Register' | tr -s ' ')" >> $T
done; done
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base= --variant nobar=BIN=build-gpu/octrace-nobar --variant regen2=BIN=build-gpu/octrace-regen2)
ab() { name=$1; shift; timeout 80 python3 tools/ab_render.py --octrace $A --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|nobar|regen2) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
tar czf $OUT/results.tgz -C /tmp res; cat $T
