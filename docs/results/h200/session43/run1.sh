# Session 43 run1: the meshes' octree leaves two references a trip (log
# 137's probes lp1-lp3 on 49eab8a) against HEAD: device time on the four
# meshes (5 rounds), the images, the pipelines' registers.
# Pack: tools/gpu_pack.sh lp1=docs/results/h200/session43/leafpair1.patch
#   lp2=... lp3=... (its COMMIT). Carried: .gl, .gpub, .assets.
# Expectations in expected.md (run1).
source tools/gpu_run.sh
V=(--variant "head=" --variant "lp1=BIN=build-gpu/octrace-lp1" --variant "lp2=BIN=build-gpu/octrace-lp2"
   --variant "lp3=BIN=build-gpu/octrace-lp3")
mesh_ab
for v in lp1 lp2 lp3; do
  same_image "engine $v" $B build-gpu/octrace-$v $S --scene .assets/2CylinderEngine.glb --accel octree
  same_image "balloon $v" $B build-gpu/octrace-$v $S --scene .assets/balloon/scene.gltf --accel octree
done
for b in $B build-gpu/octrace-lp1 build-gpu/octrace-lp2 build-gpu/octrace-lp3; do
  echo "$(basename $b) engine: $($b render $S --scene .assets/2CylinderEngine.glb --accel octree --pipeline-stats --json -q -o $R/x.pfm 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
done
rm -f $R/x.pfm
gpu_finish
