# Session 19 on the H200, run 8 (expected.md): throwaway V (node and sphere
# buffers read as whole vectors) against the kept code, both structures;
# images compared; V's pipeline cache dumped (tools/nvidia_sass.py unpack).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "kept=" --variant "V=BIN=build-gpu/var/V")
P0="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu"; P="$P0 --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab peer_octree $P --accel octree
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab balloon $S --scene .assets/balloon/scene.gltf --accel octree
ab engine $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=150 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
for a in bvh octree; do
  $B render $P0 --size 320x180 --spp 8 --accel $a -q -o $R/k.pfm
  OCTRACE_DUMP_PIPELINE_CACHE=$OUT/cache_v_$a.bin build-gpu/var/V render $P0 --size 320x180 --spp 8 --accel $a -q -o $R/v.pfm
  cmp $R/k.pfm $R/v.pfm && echo "V identical $a" >> $T || echo "V DIFFERENT $a" >> $T
done
rm -f $R/*.pfm
gpu_finish
