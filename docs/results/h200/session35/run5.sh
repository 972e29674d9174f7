# Session 35, run 5 (asked of an H100: the goals' card): the peer side by
# side with both structures and `bench` (spheres to 10M, the meshes) at
# 3825c45 (cb8d691's code, log 116's lanes rule), as run 3 did on an H200;
# and the sample lanes where every round is full (16 samples a dispatch at
# 1200x800; the peer's scene takes 8), to see whether 8 lanes gain there.
# Expectations: expected.md. Carried: .gl, .gpub, .assets, .peers.
source tools/gpu_run.sh
(cd .peers/karim && ./build.sh > "$R/peer_build.log" 2>&1); echo "peer build rc=$?" >> $T
peer peer_bvh --accel bvh
peer peer_octree --accel octree
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 > $OUT/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E " ms" $OUT/spheres.log | grep -v "^#" | tail -6 >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E "rays/s$" $OUT/meshes.log >> $T
timeout 150 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 > $OUT/spheres10m.log 2>&1
echo "bench 10M rc=$?" >> $T; grep -E " ms" $OUT/spheres10m.log | grep -v '^#' | tail -3 >> $T
S16="--size 1200x800 --spp 16 --depth 50 --device gpu"
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant "auto=" --variant "lanes8=-- --sample-lanes 8" --variant "lanes2=-- --sample-lanes 2")
AB_TIMEOUT=120 ab l16_peer_bvh $P --accel bvh
AB_TIMEOUT=120 ab l16_peer_octree $P --accel octree
for a in octree bvh; do
  ab l16_s488_$a $S16 --spheres 488 --radius 0.1 --accel $a
  ab l16_s8000_$a $S16 --spheres 8000 --radius 0.1 --accel $a
  ab l16_balloon_$a $S16 --scene .assets/balloon/scene.gltf --accel $a
  ab l16_engine_$a $S16 --scene .assets/2CylinderEngine.glb --accel $a
done
gpu_finish
