# Log 42 on the H200: octree against BVH with `octrace bench` (spheres and
# the two meshes), as docs/performance.md's octree/BVH table.
# Carried: .gl, .gpub (bin.tgz as run3.sh), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,128000,1000000 --radius 0.1 --csv $R/bvh_spheres.csv > $R/bvh_spheres.md 2>$R/bvh.log; echo "bench spheres rc=$?" >> $T; tail -10 $R/bvh_spheres.md >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/bvh_meshes.csv > $R/bvh_meshes.md 2>> $R/bvh.log; echo "bench meshes rc=$?" >> $T; tail -6 $R/bvh_meshes.md >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
