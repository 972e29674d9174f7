# Four candidate changes against 010c464 on the H200 (A/B of five builds
# alternating, 5 rounds, device time), with the pipelines' statistics.
# Carried: .gl, .gpub (var.tgz: octrace-{base,top,top2,pack,leafpush}, COMMIT), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/var.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base
$A devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V="--variant base="; for v in top top2 pack leafpush; do V="$V --variant $v=BIN=build-gpu/octrace-$v"; done
ab() { name=$1; shift; timeout 100 python3 tools/ab_render.py --octrace $A --rounds 5 --render "$*" $V --out /tmp/ab_$name.md > /tmp/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|top|top2|pack|leafpush) ' /tmp/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
for v in base top top2 pack leafpush; do for sc in tools/scenes/peer_field.json .assets/2CylinderEngine.glb; do
  timeout 30 build-gpu/octrace-$v render --scene $sc --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png > /tmp/ps_${v}_$(basename $sc).txt 2>&1
  echo "stats $v $(basename $sc): $(grep -E '^pipeline' /tmp/ps_${v}_$(basename $sc).txt | tr -s ' ' | tr '\n' ';')" >> $T
done; done
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab s8000 --spheres 8000 --radius 0.1 $S
tar czf $OUT/ab.tgz -C /tmp $(cd /tmp && ls ab_*.md ab_*.log ps_*.txt); cat $T
