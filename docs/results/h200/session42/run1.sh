# Session 42 run1: the leaf rule's probe (leaf_rule.patch, build-gpu/
# octrace-rule, settings by environment) against the defaults and session
# 41's refs 12 / leaf 20 on four meshes: device time, bytes and build time,
# the images.
# Pack: tools/gpu_pack.sh rule=docs/results/h200/session42/leaf_rule.patch
# (its COMMIT). Carried: .gl, .gpub, .assets. Expectations in expected.md (run1).
source tools/gpu_run.sh
P=build-gpu/octrace-rule
rule() { echo "BIN=$P OCTRACE_TMP_TAU=0 OCTRACE_TMP_SMALL=$2 OCTRACE_TMP_FRAC=$3 -- --octree-refs $1 --octree-leaf 10"; }
V=(--variant "old=" --variant "r12l20=-- --octree-refs 12 --octree-leaf 20"
   --variant "r12s20=$(rule 12 20 0.75)" --variant "r12s30=$(rule 12 30 0.9)" --variant "r16s30=$(rule 16 30 0.9)"
   --variant "r16s40=$(rule 16 40 0.9)" --variant "r20s30=$(rule 20 30 0.75)")
mesh_ab
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf "$R/grid.glb" "$R/grid400.glb"; do
  n=$(basename "$sc")
  $B render $S --scene "$sc" --accel octree --json -o "$R/img_old.pfm" > "$R/json.txt" 2>/dev/null
  echo "$n [old]: $(python3 -c "import json; o=json.load(open('$R/json.txt'))['octree']; print(round(o['bytes_per_primitive'], 1), 'bytes/triangle', round(o['build_ms']), 'ms build')")" >> "$T"
  for v in "12 30 0.9" "16 40 0.9" "20 30 0.75"; do
    set -- $v
    env OCTRACE_TMP_TAU=0 OCTRACE_TMP_SMALL=$2 OCTRACE_TMP_FRAC=$3 $P render $S --scene "$sc" --accel octree --octree-refs $1 --octree-leaf 10 --json -o "$R/img_new.pfm" > "$R/json.txt" 2>/dev/null
    echo "$n [rule $v]: $(python3 -c "import json; o=json.load(open('$R/json.txt'))['octree']; print(round(o['bytes_per_primitive'], 1), 'bytes/triangle', round(o['build_ms']), 'ms build')") $(cmp -s "$R/img_old.pfm" "$R/img_new.pfm" && echo 'image identical' || echo "image DIFFERS: $($B compare "$R/img_old.pfm" "$R/img_new.pfm" 2>&1 | tr '\n' ' ')")" >> "$T"
  done
  rm -f "$R/img_old.pfm" "$R/img_new.pfm"
done
rm -f "$R/grid.glb" "$R/grid400.glb"
gpu_finish
