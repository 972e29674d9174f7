# Session 40 run2: a probe of the engine's octree, leaf size against
# references a triangle (speed; bytes a triangle against issue 11's bound
# of 48 were measured on the CPU device, the same host-built trees; the
# GPU's own `render --json` rows are kept as a check). Pack: 75b8957
# (run1's). Carried: .gl, .gpub, .assets. Expectations in expected.md (run2).
source tools/gpu_run.sh
E=.assets/2CylinderEngine.glb
FLAGS=("" "--octree-leaf 16" "--octree-leaf 24" "--octree-refs 12" "--octree-refs 12 --octree-leaf 20"
       "--octree-refs 12 --octree-leaf 24" "--octree-refs 16 --octree-leaf 20" "--octree-refs 16 --octree-leaf 24"
       "--octree-refs 24 --octree-leaf 24")
V=()
for f in "${FLAGS[@]}"; do
  name=$(echo "${f:-default}" | sed 's/--octree-//g; s/ //g')
  V+=(--variant "$name=-- $f")
done
AB_TIMEOUT=420 ab engine_leaf_refs $S --scene $E --accel octree
for f in "${FLAGS[@]}"; do
  $B render $S --scene $E --accel octree --spp 1 $f --json --out /tmp/e.png > "$R/json.txt" 2>/dev/null
  echo "octree [${f:-default}]: $(python3 -c "import json; o=json.load(open('$R/json.txt'))['octree']; print(round(o['bytes_per_primitive'], 1), 'bytes/triangle', o['nodes'], 'nodes', o['refs'], 'refs')")" >> "$T"
done
gpu_finish
