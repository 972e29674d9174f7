# Session 47 run1: the tail's subgroup stage (--tail-subgroup) against off,
# with session 46's run7 (--tail-fill, --tail-step 2) folded in; the
# engine and the balloon, then the sphere fields; tools/ab_render.py 5
# rounds, device time; and whether the image is the same, bit for bit.
# Expectations in expected.md (run1).
source tools/gpu_run.sh
V=(--variant "off=-- --tail-subgroup off" --variant "auto=" --variant "sub32k=-- --tail-subgroup 32768"
   --variant "sub2k=-- --tail-subgroup 2048" --variant "fill65k=-- --tail-fill 65536" --variant "step2=-- --tail-step 2")
AB_ROUNDS=5
AB_TIMEOUT=150 ab engine_sub $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=150 ab balloon_sub $S --scene .assets/balloon/scene.gltf --accel octree
V=(--variant "off=-- --tail-subgroup off" --variant "auto=")
ab s488_sub $S --spheres 488 --radius 0.1 --accel octree
ab s8000_sub $S --spheres 8000 --radius 0.1 --accel octree
for sc in "--scene .assets/2CylinderEngine.glb" "--scene .assets/balloon/scene.gltf" "--spheres 488 --radius 0.1" \
          "--spheres 8000 --radius 0.1" "--spheres 488"; do
  "$B" render $S $sc --tail-subgroup off -q -o "$R/off.pfm"
  "$B" render $S $sc -q -o "$R/auto.pfm" --json > "$R/auto.json"
  cmp -s "$R/off.pfm" "$R/auto.pfm" && r=identical || r=DIFFERENT
  echo "image $sc: $r (tail_subgroup $(grep -o '"tail_subgroup": [0-9]*' "$R/auto.json"))" >> "$T"
done
rm -f "$R"/*.pfm
gpu_finish
