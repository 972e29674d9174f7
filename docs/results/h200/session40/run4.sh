# Session 40 run4: the octree pairs that keep both glTF scenes within 48
# bytes a triangle (refs 12 with leaf 20, refs 16 with leaf 22) on the
# engine and the balloon. Pack: 75b8957 (run1's). Carried: .gl, .gpub,
# .assets. Expectations in expected.md (run4).
source tools/gpu_run.sh
V=(--variant "default=" --variant "refs12leaf20=-- --octree-refs 12 --octree-leaf 20"
   --variant "refs16leaf22=-- --octree-refs 16 --octree-leaf 22")
AB_TIMEOUT=300 ab engine $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=300 ab balloon $S --scene .assets/balloon/scene.gltf --accel octree
for f in "" "--octree-refs 12 --octree-leaf 20" "--octree-refs 16 --octree-leaf 22"; do
  for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do
    $B render $S --scene $sc --accel octree --spp 1 $f --json --out /tmp/e.png > "$R/json.txt" 2>/dev/null
    echo "$(basename $sc) [${f:-default}]: $(python3 -c "import json; o=json.load(open('$R/json.txt'))['octree']; print(round(o['bytes_per_primitive'], 1), 'bytes/triangle')")" >> "$T"
  done
done
gpu_finish
