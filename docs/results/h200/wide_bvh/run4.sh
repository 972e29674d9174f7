# Log 54 on the H200, run 4: the commit as kept (app/octrace: the meshes'
# BVHs four-wide, the top level four-wide over instances only) against
# fc632c6 (octrace-base), --accel bvh, 5 rounds, on the engine (the one
# scene whose code differs from run 3's split: its top level of instances
# is four-wide now; the balloon's single instance and the sphere fields run
# what run 3 measured); its image; the whole hard-case suite on the GPU.
# (Cut to this after a failed start left 645 s of device time.)
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=60
V=(--variant base=BIN=$A --variant kept=BIN=$B)
ab engine --scene .assets/2CylinderEngine.glb $S --accel bvh
for sc in "--scene .assets/2CylinderEngine.glb --spp 10"; do
  for v in $A $B; do timeout 30 $v render $sc --accel bvh --size 480x270 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "identity $sc: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T
done
export OCTRACE_TEST_DEVICE=gpu
suite hardcases_test 440
gpu_finish
