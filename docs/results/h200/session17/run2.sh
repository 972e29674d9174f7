# Session 17 on the H200, run 2: the scene's arrays through buffer device
# addresses (OCTRACE_FORCE_SPLIT=1, split_bda.patch) and descriptors with
# VK_EXT_pipeline_robustness's storage buffers DISABLED
# (OCTRACE_ROBUSTNESS_OFF=1, robustness_off.patch) against descriptors,
# one binary; the bda variant's machine code (OCTRACE_DUMP_PIPELINE_CACHE).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "desc=" --variant "bda=OCTRACE_FORCE_SPLIT=1" --variant "norobust=OCTRACE_ROBUSTNESS_OFF=1")
P0="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu"; P="$P0 --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab peer_octree $P --accel octree
ab s488_octree $S --spheres 488 --radius 0.1 --accel octree
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab engine $S --scene .assets/2CylinderEngine.glb
ab balloon $S --scene .assets/balloon/scene.gltf
for a in bvh octree; do
  $B render $P0 --size 320x180 --spp 8 --accel $a -o $R/desc_$a.pfm -q
  OCTRACE_FORCE_SPLIT=1 OCTRACE_DUMP_PIPELINE_CACHE=$R/cache_bda_$a.bin $B render $P0 --size 320x180 --spp 8 --accel $a -o $R/bda_$a.pfm -q --pipeline-stats --json > $R/bda_$a.json
  OCTRACE_ROBUSTNESS_OFF=1 OCTRACE_DUMP_PIPELINE_CACHE=$R/cache_norobust_$a.bin $B render $P0 --size 320x180 --spp 8 --accel $a -o $R/norobust_$a.pfm -q
  cmp $R/desc_$a.pfm $R/bda_$a.pfm && echo "bda identical $a" >> $T || echo "bda DIFFERENT $a" >> $T
  cmp $R/desc_$a.pfm $R/norobust_$a.pfm && echo "norobust identical $a" >> $T || echo "norobust DIFFERENT $a" >> $T
done
rm -f $R/*.pfm
gpu_finish
