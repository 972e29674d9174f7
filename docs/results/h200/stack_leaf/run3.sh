# On 476acad (log 40) on the H200: leaf primitives tested in pairs (both
# references loaded first; the sphere walk only, and with the mesh walk too)
# and octant culling off, A/B against 476acad (5 rounds, device time); then
# octree against BVH on every family with `octrace bench`.
# Carried: .gl, .gpub (bin.tgz of run2.sh and pair.tgz: octrace-pair,
# octrace-pairmesh), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu; tar xzf .gpub/pair.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
for v in pair pairmesh; do for sc in tools/scenes/peer_field.json .assets/2CylinderEngine.glb; do
  echo "regs $v $(basename $sc): $(timeout 30 build-gpu/octrace-$v render --scene $sc --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png 2>&1 | grep -E '^pipeline  Register' | tr -s ' ')" >> $T
done; done
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base= --variant pair=BIN=build-gpu/octrace-pair --variant pairmesh=BIN=build-gpu/octrace-pairmesh --variant "cull_off=-- --octant-culling off")
ab() { name=$1; shift; timeout 80 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|pair|pairmesh|cull_off) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
timeout 120 $B bench --device gpu --accel octree,bvh --spheres 488,8000,128000,1000000 --radius 0.1 --csv $R/bvh_spheres.csv > $R/bvh_spheres.md 2>$R/bvh.log; echo "bench spheres rc=$?" >> $T; tail -10 $R/bvh_spheres.md >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/bvh_meshes.csv > $R/bvh_meshes.md 2>> $R/bvh.log; echo "bench meshes rc=$?" >> $T; tail -6 $R/bvh_meshes.md >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
