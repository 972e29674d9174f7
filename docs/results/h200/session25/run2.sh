# Session 25 on the H200, run 2 (expected.md): the triangle test as one
# matrix with its products written out (log 72), the fused dot of run 1 beside it. Carried: .gl,
# .gpub (bin.txz: app/octrace = 90102c5 + sheared(), var/fused = 90102c5, octrace-base = c982fe1), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "fused=BIN=build-gpu/var/fused" --variant "new=")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do for a in octree bvh; do
  AB_ROUNDS=7 AB_TIMEOUT=160 ab ${sc%%:*}_$a $S --scene ${sc#*:} --accel $a
  same_image ${sc%%:*}_$a $A $B $S --scene ${sc#*:} --accel $a
done; done
gpu_finish
