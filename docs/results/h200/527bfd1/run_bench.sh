# Octree against BVH on every scene family at 527bfd1 (after optimisation
# log 38) on the H200, with `octrace bench` (octree and BVH alternating per
# row), and the octree's leaf size again now that leaves are tested in
# while-while form (A/B of --octree-leaf 4 / 10 / 16, 5 rounds).
# Carried: .gl, .gpub (bin.tgz, as run.sh), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res4; rm -rf $R; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
timeout 120 $B bench --device gpu --accel octree,bvh --spheres 488,8000,128000,1000000 --radius 0.1 --csv $R/bvh_spheres.csv > $R/bvh_spheres.md 2>$R/bvh.log; echo "bench spheres rc=$?"; tail -10 $R/bvh_spheres.md
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/bvh_meshes.csv > $R/bvh_meshes.md 2>> $R/bvh.log; echo "bench meshes rc=$?"; tail -6 $R/bvh_meshes.md
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
for sc in "peer|--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu" "s488|--spheres 488 --radius 0.1 $S" "engine|--scene .assets/2CylinderEngine.glb $S"; do
  n=${sc%%|*}; a=${sc#*|}
  timeout 70 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$a" --variant leaf10= --variant "leaf4=-- --octree-leaf 4" --variant "leaf16=-- --octree-leaf 16" --out $R/leaf_$n.md > $R/leaf_$n.log 2>&1
  echo "leaf $n: $(grep -E '^\| leaf' $R/leaf_$n.md | cut -d'|' -f2,5,9 | tr '\n' ' ')"
done
tar czf $OUT/results.tgz -C /tmp res4; ls -la $OUT
