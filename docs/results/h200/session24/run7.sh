# Session 24 on the H200, run 7 (expected.md): auto lanes 4 for meshes
# with the tail queue against 22020f6. Carried: .gl, .gpub (bin.txz:
# app/octrace = the change, octrace-base = 22020f6), .assets. Prelude:
# tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "new=")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do for a in octree bvh; do
  AB_ROUNDS=7 AB_TIMEOUT=100 ab ${sc%%:*}_$a $S --scene ${sc#*:} --accel $a
done; done
same_image engine_octree $A $B $S --scene .assets/2CylinderEngine.glb --accel octree
same_image balloon_bvh $A $B $S --scene .assets/balloon/scene.gltf --accel bvh
gpu_finish
