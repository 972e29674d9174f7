# Session 43 run2: fewer registers in the mesh pipeline (log 137's probes
# ident, shear6 and both on HEAD) against HEAD: device time on the four
# meshes (5 rounds), the images, the pipelines' registers.
# Pack: tools/gpu_pack.sh ident=docs/results/h200/session43/ident.patch
#   shear6=.../shear6.patch both=.../ident_shear6.patch (its COMMIT).
# Carried: .gl, .gpub, .assets. Expectations in expected.md (run2).
source tools/gpu_run.sh
V=(--variant "head=" --variant "ident=BIN=build-gpu/octrace-ident" --variant "shear6=BIN=build-gpu/octrace-shear6"
   --variant "both=BIN=build-gpu/octrace-both")
mesh_ab
for v in ident shear6 both; do
  same_image "engine $v" $B build-gpu/octrace-$v $S --scene .assets/2CylinderEngine.glb --accel octree
  same_image "balloon $v" $B build-gpu/octrace-$v $S --scene .assets/balloon/scene.gltf --accel octree
done
for b in $B build-gpu/octrace-ident build-gpu/octrace-shear6 build-gpu/octrace-both; do
  echo "$(basename $b) engine: $($b render $S --scene .assets/2CylinderEngine.glb --accel octree --pipeline-stats --json -q -o $R/x.pfm 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
  echo "$(basename $b) grid400: $($b render $S --scene $R/grid400.glb --accel octree --pipeline-stats --json -q -o $R/x.pfm 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
done
rm -f $R/x.pfm $R/grid.glb $R/grid400.glb
gpu_finish
