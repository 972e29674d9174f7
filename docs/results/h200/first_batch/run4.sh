# Log 42 on the H200: `render` A/B against 075c55a (5 rounds, device time),
# the CUDA peer side by side, the sphere-count series and the glTF rays/s.
# Carried: .gl, .gpub (bin.tgz as run3.sh), .assets, .peers.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base; B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
(cd .peers/karim && ./build.sh > $R/peer_build.txt 2>&1) &
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base=BIN=$A --variant log42=)
ab() { name=$1; shift; timeout 90 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|log42) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
wait
timeout 150 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer --rounds 5 > $R/peer.log 2>&1; echo "peer rc=$?" >> $T; tail -4 $R/peer/peer_compare.md >> $T
timeout 90 $B bench --device gpu --accel octree --spheres 488,8000,1000000,10000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1; echo "bench rc=$?" >> $T; tail -8 $R/spheres.log >> $T
timeout 60 $B bench --device gpu -q --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --accel octree --repeat 5 --csv $R/meshes.csv > $R/meshes.md 2>&1; echo "meshes rc=$?" >> $T; cat $R/meshes.md >> $T
rm -f $R/peer/*.ppm $R/peer/*.pfm $R/peer/*.png; tar czf $OUT/results.tgz -C /tmp res; cat $T
