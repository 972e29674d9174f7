# Session 25 on the H200, run 1 (expected.md): the triangle test as one
# matrix (log 72) against c982fe1, and the GPU suites with it. Carried: .gl,
# .gpub (bin.txz: app/octrace = 90102c5, octrace-base = c982fe1), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "new=")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do for a in octree bvh; do
  AB_ROUNDS=7 AB_TIMEOUT=100 ab ${sc%%:*}_$a $S --scene ${sc#*:} --accel $a
  same_image ${sc%%:*}_$a $A $B $S --scene ${sc#*:} --accel $a
done; done
gpu_suites
gpu_finish
