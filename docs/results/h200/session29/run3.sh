# Session 29 on the H200, run 3: `bench` of the goals' sphere fields and
# meshes, both structures, at HEAD. Carried: .gl, .gpub (bin.txz), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 > $OUT/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E "ms" $OUT/spheres.log | grep -v "^#" | tail -8 >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E "rays/s$" $OUT/meshes.log >> $T
gpu_finish
