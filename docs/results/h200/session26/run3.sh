# Session 26 on the H200, run 3 (expected.md): the octree's split budget
# shared by references x (half-area)^p (vshare.patch, one binary, the
# environment picks p). Carried: .gl, .gpub (bin.txz), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=" --variant "cbrt=OCTRACE_X_SHARE=1 OCTRACE_X_P=0.3333" --variant "sqrt=OCTRACE_X_SHARE=1 OCTRACE_X_P=0.5")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  AB_ROUNDS=7 AB_TIMEOUT=150 ab ${sc%%:*}_octree $S --scene ${sc#*:} --accel octree
  $B render $S --scene ${sc#*:} -q -o $R/a.pfm
  OCTRACE_X_SHARE=1 OCTRACE_X_P=0.3333 $B render $S --scene ${sc#*:} -q -o $R/b.pfm
  cmp -s $R/a.pfm $R/b.pfm && echo "${sc%%:*} cbrt identical" >> $T || echo "${sc%%:*} cbrt DIFFERENT" >> $T
  rm -f $R/a.pfm $R/b.pfm
done
M="--device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb"
OCTRACE_X_SHARE=1 OCTRACE_X_P=0.3333 timeout 150 $B bench $M > $OUT/bench_meshes_cbrt.txt 2>&1; echo "bench cbrt rc=$?" >> $T; grep -E "rays/s$" $OUT/bench_meshes_cbrt.txt >> $T
gpu_finish
