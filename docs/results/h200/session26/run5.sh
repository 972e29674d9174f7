# Session 26 on the H200, run 5 (expected.md): `bench` of the sphere
# fields (488, 8,000, 1M, r = 0.1, both structures; 10M with the BVH) and
# of the meshes, at bd2f5fc's code. Carried: .gl, .gpub (bin.txz),
# .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 --csv $R/spheres.csv > $OUT/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E "ms" $OUT/spheres.log | grep -v "^#" | tail -8 >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E "rays/s$" $OUT/meshes.log >> $T
timeout 240 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 > $OUT/spheres_10m.log 2>&1
echo "bench 10M rc=$?" >> $T; grep -E "ms" $OUT/spheres_10m.log | grep -v "^#" | tail -3 >> $T
gpu_finish
