set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace; O=build-gpu/app/octrace-old
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
ab() { name=$1; shift; timeout 75 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" --variant "axis=BIN=$O" --variant "exact=" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name: $(tail -2 $R/ab_$name.md | cut -d'|' -f2,5 | tr '\n' ' ')"; }
{
timeout 90 python3 tools/ab_render.py --octrace $B --rounds 5 --render "--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu" --variant "axis=BIN=$O" --variant "exact=" --variant "bvh=-- --accel bvh" --out $R/ab_peer.md > $R/ab_peer.log 2>&1; echo "peer: $(tail -3 $R/ab_peer.md | cut -d'|' -f2,5 | tr '\n' ' ')"
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab s128k --spheres 128000 --radius 0.1 $S
ab s1m --spheres 1000000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
} | tee $R/summary.txt
timeout 200 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer --rounds 5 > $R/peer.log 2>&1; echo "peer rc=$?"; tail -6 $R/peer/peer_compare.md
rm -f $R/peer/*.ppm $R/peer/*.pfm $R/peer/*.png; tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
