# Session 26 on the H200, run 6 (expected.md): the octree's child loop two
# children a trip (vpair.patch) against bd2f5fc. Carried: .gl, .gpub
# (bin.txz: app/octrace = bd2f5fc + vpair.patch, octrace-base = bd2f5fc),
# .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "pair=")
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
ab peer_octree $P --accel octree
same_image peer_octree $A $B $P --accel octree
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  AB_ROUNDS=7 ab ${sc%%:*}_octree $S --scene ${sc#*:} --accel octree
  same_image ${sc%%:*}_octree $A $B $S --scene ${sc#*:} --accel octree
done
AB_TIMEOUT=120 ab s1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
$B render $P --accel octree --pipeline-stats -q -o $R/x.pfm > $R/stats_pair.txt 2>&1
$A render $P --accel octree --pipeline-stats -q -o $R/x.pfm > $R/stats_base.txt 2>&1
grep -i "register" $R/stats_base.txt | head -3 | sed 's/^/base: /' >> $T
grep -i "register" $R/stats_pair.txt | head -3 | sed 's/^/pair: /' >> $T
rm -f $R/x.pfm
gpu_finish
