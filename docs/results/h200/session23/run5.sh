# Session 23 on the H200, run 5 (expected.md): the head's samples per
# dispatch on the peer's scene (throwaway var/xtail). Carried: .gl, .gpub
# (bin.txz: app/octrace = var/xtail = 8ec4de2 + xtail.patch), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
for a in bvh octree; do
  $B render $P --accel $a -q -o $R/k.pfm
  for e in OCTRACE_X_TAIL_LOG2=30 "OCTRACE_X_TAIL_LOG2=31 OCTRACE_X_TAIL_MAX=64"; do
    env $e $B render $P --accel $a -q -o $R/v.pfm
    cmp -s $R/k.pfm $R/v.pfm && echo "identical $a ($e)" >> $T || echo "DIFFERENT $a ($e)" >> $T
  done
done
rm -f $R/*.pfm
V=(--variant "d7=" --variant "d8=OCTRACE_X_TAIL_LOG2=29" --variant "d16=OCTRACE_X_TAIL_LOG2=30" --variant "d64=OCTRACE_X_TAIL_LOG2=31 OCTRACE_X_TAIL_MAX=64")
AB_TIMEOUT=150 ab peer_bvh $P --accel bvh
AB_TIMEOUT=150 ab peer_octree $P --accel octree
AB_TIMEOUT=100 ab peer_bvh_spp16 $P --accel bvh --spp 16
gpu_finish
