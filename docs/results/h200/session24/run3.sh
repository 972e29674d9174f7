# Session 24 on the H200, run 3 (expected.md): SPEC_ONE_INSTANCE against
# c66d2c9 on both meshes and structures, 7 rounds; images with and without
# it. Carried: .gl, .gpub (bin.txz: app/octrace = the new build with the
# throwaway OCTRACE_NO_ONE_INSTANCE, octrace-base = c66d2c9), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "one=" --variant "off=OCTRACE_NO_ONE_INSTANCE=1")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do for a in bvh octree; do
  AB_ROUNDS=7 AB_TIMEOUT=150 ab ${sc%%:*}_$a $S --scene ${sc#*:} --accel $a
  $B render $S --scene ${sc#*:} --accel $a -q -o $R/one.pfm
  OCTRACE_NO_ONE_INSTANCE=1 $B render $S --scene ${sc#*:} --accel $a -q -o $R/off.pfm
  cmp -s $R/one.pfm $R/off.pfm && echo "${sc%%:*} $a identical" >> $T || echo "${sc%%:*} $a DIFFERENT" >> $T
  rm -f $R/one.pfm $R/off.pfm
done; done
gpu_finish
