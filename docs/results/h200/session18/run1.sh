# Session 18 on the H200, run 1: four binaries side by side (expected.md):
# base (65a2908), R (restrict), WR (R + the binary BVH walk's header in
# registers), WRO (WR + the octree stack with headers); WRO's pipelines
# dumped for the machine code (tools/nvidia_sass.py, unpacked locally).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "R=BIN=build-gpu/var/R" --variant "WR=BIN=build-gpu/var/WR" --variant "WRO=")
P0="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu"; P="$P0 --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab peer_octree $P --accel octree
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s488_octree $S --spheres 488 --radius 0.1 --accel octree
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab engine $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon $S --scene .assets/balloon/scene.gltf --accel octree
AB_TIMEOUT=200 ab s1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
for a in bvh octree; do
  OCTRACE_DUMP_PIPELINE_CACHE=$R/cache_wro_$a.bin timeout 60 $B render $P0 --size 320x180 --spp 8 --accel $a \
    -o $R/wro_$a.pfm -q --pipeline-stats --json > $R/wro_$a.json 2> $R/wro_$a.err
  $A render $P0 --size 320x180 --spp 8 --accel $a -o $R/base_$a.pfm -q
  cmp $R/base_$a.pfm $R/wro_$a.pfm && echo "WRO identical $a" >> $T || echo "WRO DIFFERENT $a" >> $T
done
rm -f $R/*.pfm
gpu_finish
