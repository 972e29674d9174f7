# Session 19 on the H200, run 1: throwaway D (expected.md: sphere BVH leaves
# without the reference indirection) against e2ada62, with --accel bvh.
# Carried: .gl, .gpub (bin.tgz). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "D=BIN=build-gpu/var/D")
P0="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu"; P="$P0 --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s128k_bvh $S --spheres 128000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
for sc in "$P0 --size 320x180 --spp 8" "--spheres 8000 --radius 0.1 --device gpu --size 320x180 --spp 8"; do
  $A render $sc --accel bvh -q -o $R/a.pfm; build-gpu/var/D render $sc --accel bvh -q -o $R/d.pfm
  cmp $R/a.pfm $R/d.pfm && echo "D identical: $sc" >> $T || echo "D DIFFERENT: $sc" >> $T
done
rm -f $R/*.pfm
gpu_finish
