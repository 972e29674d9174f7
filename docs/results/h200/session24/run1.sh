# Session 24 on the H200, run 1 (expected.md): the engine with every
# instance baked (OCTRACE_BAKE_ALL, vbake.patch) against HEAD, both
# structures, 7 rounds. Carried: .gl, .gpub (bin.txz: app/octrace =
# vbake, octrace-base), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "same=" --variant "bake=OCTRACE_BAKE_ALL=1")
for a in bvh octree; do
  AB_ROUNDS=7 AB_TIMEOUT=150 ab engine_$a $S --scene .assets/2CylinderEngine.glb --accel $a
done
gpu_finish
