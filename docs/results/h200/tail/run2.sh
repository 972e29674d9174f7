# Log 49 on the H200: `render` A/B of the code before (base) against the
# tail queue at bounces 2, 3 (auto) and 4, 5 rounds (run2's first try, with
# the indirect dispatch read from the wrong offset, timed `--tail-depth off`
# too: within 0.6% of base), on the meshes,
# the sphere fields and the peer's scene; three scenes' identity of the auto
# form against the code before (run3 has the rest). Carried: .gl, .gpub (bin.tgz:
# app/octrace with the tail queue, octrace-base of 3c8ac7a, COMMIT), .assets.
# The prelude is tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=110
V=(--variant base=BIN=$A --variant "t2=-- --tail-depth 2"
   --variant "t3=-- --tail-depth 3" --variant "t4=-- --tail-depth 4")
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
for sc in "--scene .assets/2CylinderEngine.glb" "--scene .assets/balloon/scene.gltf" "--spheres 8000 --radius 0.1"; do
  for v in $A $B; do timeout 30 $v render $sc --size 400x300 --spp 10 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "identity $sc 10 spp: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T
done
export OCTRACE_TEST_DEVICE=gpu
timeout 60 build-gpu/tests/accel_test > $R/accel_test.txt 2>&1; echo "accel_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/accel_test.txt | tr '\n' ' ')" >> $T
timeout 60 build-gpu/tests/effects_test > $R/effects_test.txt 2>&1; echo "effects_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/effects_test.txt | tr '\n' ' ')" >> $T
gpu_finish
