# Session 43 run1: the meshes' octree leaves two references a trip (log
# 137's probes lp1-lp3 on 49eab8a) against HEAD: device time on the four
# meshes (5 rounds), the images, the pipelines' registers; and sp1 (lp1
# with the top level's sphere leaves two a trip) on three sphere fields.
# Pack: tools/gpu_pack.sh lp1=docs/results/h200/session43/leafpair1.patch
#   lp2=... lp3=... sp1=.../spherepair.patch (its COMMIT). Carried: .gl, .gpub, .assets.
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
V=(--variant "head=" --variant "sp1=BIN=build-gpu/octrace-sp1")
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
ab peer_octree $P --accel octree
ab s488_octree $S --spheres 488 --radius 0.1 --accel octree
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
same_image "peer sp1" $B build-gpu/octrace-sp1 $P --accel octree
same_image "8000 sp1" $B build-gpu/octrace-sp1 $S --spheres 8000 --radius 0.1 --accel octree
echo "sp1 peer: $(build-gpu/octrace-sp1 render $P --accel octree --pipeline-stats --json -q -o $R/x.pfm 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
echo "head peer: $($B render $P --accel octree --pipeline-stats --json -q -o $R/x.pfm 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
rm -f $R/x.pfm
gpu_finish
