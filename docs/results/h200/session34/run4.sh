# Session 34, run 4: why session 29's workgroup arrays make the walks
# 3.5-4% faster on the H100 (run 1: the arrays alone do it, the pipeline's
# registers 40 -> 47, its shared memory 1792 -> 2048 bytes; eight times
# larger arrays 57-72% slower), and the octree's leaf size over spheres
# beyond 16 (run 3: leaf 16 -6.0% on the peer's scene). Five builds of
# 75be938 (COMMIT in the pack): the arrays as in run 1 (arrays), the same
# arrays written by every invocation (live), one workgroup word behind the
# dead branch (one), lane_sample twice as large (lane2x), 16x16 workgroups
# (wg16). Expectations: expected.md beside this script. Carried: .gl,
# .gpub, .assets.
source tools/gpu_run.sh
V=(--variant "head=" --variant "arrays=BIN=build-gpu/octrace-arrays" --variant "live=BIN=build-gpu/octrace-live"
   --variant "one=BIN=build-gpu/octrace-one" --variant "lane2x=BIN=build-gpu/octrace-lane2x"
   --variant "wg16=BIN=build-gpu/octrace-wg16")
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
AB_TIMEOUT=150 ab peer_octree $P --accel octree
AB_TIMEOUT=150 ab peer_bvh $P --accel bvh
AB_TIMEOUT=100 ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
AB_TIMEOUT=100 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=120 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=120 ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
for v in $B build-gpu/octrace-arrays build-gpu/octrace-live build-gpu/octrace-one build-gpu/octrace-lane2x build-gpu/octrace-wg16; do
  for a in octree bvh; do
    echo "$(basename $v) $a: $($v render $P --accel $a --pipeline-stats --json -q --out $R/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
  done
done
for a in octree bvh; do
  same_image "peer $a head/arrays" $B build-gpu/octrace-arrays --size 600x400 --spp 4 --device gpu --scene tools/scenes/peer_field.json --accel $a
  same_image "peer $a head/wg16" $B build-gpu/octrace-wg16 --size 600x400 --spp 4 --device gpu --scene tools/scenes/peer_field.json --accel $a
done
same_image "engine octree head/wg16" $B build-gpu/octrace-wg16 --size 300x200 --spp 4 --device gpu --scene .assets/2CylinderEngine.glb
rm -f $R/ps.png
V=(--variant "auto=" --variant "leaf12=-- --octree-leaf 12" --variant "leaf16=-- --octree-leaf 16"
   --variant "leaf24=-- --octree-leaf 24" --variant "leaf32=-- --octree-leaf 32")
AB_TIMEOUT=150 ab leaf_peer_octree $P --accel octree
AB_TIMEOUT=100 ab leaf_s488_octree $S --spheres 488 --radius 0.1 --accel octree
AB_TIMEOUT=100 ab leaf_s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=150 ab leaf_s1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
gpu_finish
