# Session 49 run1, in the order of what matters most if the device time
# runs out: the peer side by side (the camera's tiles on by auto), the
# A/B of the tiles against off on the peer's scene (whole paths and camera
# rays alone), the images, the sphere fields of the goals.
# Expectations in expected.md (run1).
source tools/gpu_run.sh
peer_both
V=(--variant "off=-- --camera-tiles off" --variant "auto=")
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
ab peer_bvh_tiles $PEER --accel bvh
ab peer_octree_tiles $PEER --accel octree
PEER1="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 1 --rr-depth 1 --device gpu"
ab peer_bvh_depth1 $PEER1 --accel bvh
ab peer_octree_depth1 $PEER1 --accel octree
for a in bvh octree; do
  "$B" render $PEER --accel $a --camera-tiles off -q -o "$R/img_off.pfm"
  "$B" render $PEER --accel $a -q -o "$R/img_auto.pfm" --json > "$R/peer_$a.json"
  cmp -s "$R/img_off.pfm" "$R/img_auto.pfm" && echo "image peer $a: off and auto identical (auto: $(grep -o '"camera_tiles": "[a-z]*"' "$R/peer_$a.json"))" >> "$T" || echo "image peer $a: DIFFERENT" >> "$T"
done
"$B" render $S --spheres 8000 --radius 0.1 --accel bvh --camera-tiles off -q -o "$R/img_off.pfm"
"$B" render $S --spheres 8000 --radius 0.1 --accel bvh -q -o "$R/img_auto.pfm" --json > "$R/s8000.json"
cmp -s "$R/img_off.pfm" "$R/img_auto.pfm" && echo "image 8000 bvh: off and auto identical (auto: $(grep -o '"camera_tiles": "[a-z]*"' "$R/s8000.json"))" >> "$T" || echo "image 8000 bvh: DIFFERENT" >> "$T"
ab s488_tiles $S --spheres 488 --radius 0.1 --accel bvh
ab s488_tiles_octree $S --spheres 488 --radius 0.1 --accel octree
ab s8000_tiles $S --spheres 8000 --radius 0.1 --accel bvh
ab s8000_tiles_octree $S --spheres 8000 --radius 0.1 --accel octree
gpu_finish
