# Prepared in session 33: the GPU suites at 75be938 (the top level's BVH
# is built with node cost 2 since log 107's change; the shaders are those
# of 819b6d5), the peer side by side with both structures, and `bench`.
# Carried: .gl, .gpub, .assets, .peers.
source tools/gpu_run.sh
gpu_suites
peer peer_bvh --accel bvh
peer peer_octree --accel octree
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 > $OUT/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E " ms" $OUT/spheres.log | grep -v "^#" | tail -6 >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E "rays/s$" $OUT/meshes.log >> $T
gpu_finish
