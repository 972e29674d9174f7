# Session 19 on the H200, run 5 (expected.md): throwaway T (the hit's scene
# index kept in a register) against the kept code (70183fd), D and e2ada62,
# --accel bvh.
# Carried: .gl, .gpub (bin.tgz). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "kept=" --variant "T=BIN=build-gpu/var/T" --variant "D=BIN=build-gpu/var/D" --variant "base=BIN=$A")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s128k_bvh $S --spheres 128000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
for v in kept T; do
  b=$B; [ $v = T ] && b=build-gpu/var/T
  $b render --spheres 8000 --radius 0.1 --device gpu --size 320x180 --spp 8 --accel bvh -q -o $R/$v.pfm
done
cmp $R/kept.pfm $R/T.pfm && echo "T identical" >> $T || echo "T DIFFERENT" >> $T
rm -f $R/*.pfm
gpu_finish
