# Session 35, run 3: the tail's samples per head dispatch on the peer's
# scene (a probe, tail_samples_env.patch: OCTRACE_TAIL_SAMPLES), log 116's
# lanes rule against the old auto (`--sample-lanes 4`) on every family,
# the peer side by side with both structures and `bench` (spheres to 10M,
# the meshes) at 3825c45 (cb8d691's code). Expectations: expected.md. Carried: .gl, .gpub,
# .assets, .peers.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
C=build-gpu/octrace-tailsamples
V=(--variant "ts8=" --variant "ts16=BIN=$C OCTRACE_TAIL_SAMPLES=16" --variant "ts32=BIN=$C OCTRACE_TAIL_SAMPLES=32"
   --variant "ts4=BIN=$C OCTRACE_TAIL_SAMPLES=4")
AB_TIMEOUT=150 ab ts_peer_bvh $P --accel bvh
AB_TIMEOUT=150 ab ts_peer_octree $P --accel octree
V=(--variant "auto=" --variant "lanes4=-- --sample-lanes 4")
for a in octree bvh; do
  ab s488_$a $S --spheres 488 --radius 0.1 --accel $a
  ab s8000_$a $S --spheres 8000 --radius 0.1 --accel $a
  AB_TIMEOUT=120 ab s1m_$a $S --spheres 1000000 --radius 0.1 --accel $a
  ab balloon_$a $S --scene .assets/balloon/scene.gltf --accel $a
  ab engine_$a $S --scene .assets/2CylinderEngine.glb --accel $a
done
(cd .peers/karim && ./build.sh > "$R/peer_build.log" 2>&1); echo "peer build rc=$?" >> $T
peer peer_bvh --accel bvh
peer peer_octree --accel octree
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 > $OUT/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E " ms" $OUT/spheres.log | grep -v "^#" | tail -6 >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E "rays/s$" $OUT/meshes.log >> $T
timeout 150 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 > $OUT/spheres10m.log 2>&1
echo "bench 10M rc=$?" >> $T; grep -E " ms" $OUT/spheres10m.log | grep -v '^#' | tail -3 >> $T
gpu_finish
