# Prepared in session 33 (after runs 9 and 10: session 29's shared-stack
# build at N = 0 took the peer's scene 3.5-4% below HEAD with both
# structures, and no shader differs between its base and HEAD): which part
# of that patch does it. Five builds of 75be938 (COMMIT in the pack):
# the whole patch (sst), its two workgroup arrays alone (arrays), the
# same arrays eight times larger (arrays8), its stack macros alone
# (macros), the binary BVH pop as one uvec2 (pop); and
# HEAD and sst with the module specialised before the driver sees it
# (OCTRACE_SPECIALIZE=1: log 20's light passes, never timed on a GPU).
# Expectations: expected.md beside this script. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
V=(--variant "head=" --variant "sst=BIN=build-gpu/octrace-sst" --variant "arrays=BIN=build-gpu/octrace-arrays"
   --variant "arrays8=BIN=build-gpu/octrace-arrays8"
   --variant "macros=BIN=build-gpu/octrace-macros" --variant "pop=BIN=build-gpu/octrace-pop"
   --variant "spec=OCTRACE_SPECIALIZE=1" --variant "sst_spec=BIN=build-gpu/octrace-sst OCTRACE_SPECIALIZE=1")
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
AB_TIMEOUT=150 ab peer_octree $P --accel octree
AB_TIMEOUT=150 ab peer_bvh $P --accel bvh
AB_TIMEOUT=120 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=120 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
for v in $B build-gpu/octrace-sst build-gpu/octrace-arrays build-gpu/octrace-arrays8 build-gpu/octrace-macros; do
  for a in octree bvh; do
    echo "$(basename $v) $a: $($v render $P --accel $a --pipeline-stats --json -q --out $R/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
  done
done
for a in octree bvh; do
  echo "octrace specialised $a: $(OCTRACE_SPECIALIZE=1 $B render $P --accel $a --pipeline-stats --json -q --out $R/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
done
same_image "peer octree head/sst" $B build-gpu/octrace-sst --size 600x400 --spp 4 --device gpu --scene tools/scenes/peer_field.json --accel octree
for a in octree bvh; do  # the module specialised before the driver: the same image?
  F="--size 600x400 --spp 4 --device gpu --scene tools/scenes/peer_field.json --accel $a"
  $B render $F -q -o $R/h.pfm; OCTRACE_SPECIALIZE=1 $B render $F -q -o $R/hs.pfm
  cmp -s $R/h.pfm $R/hs.pfm && echo "peer $a head/specialised identical" >> $T || echo "peer $a head/specialised DIFFERENT" >> $T
  rm -f $R/h.pfm $R/hs.pfm
done
same_image "peer bvh head/sst" $B build-gpu/octrace-sst --size 600x400 --spp 4 --device gpu --scene tools/scenes/peer_field.json --accel bvh
rm -f $R/ps.png
gpu_finish
