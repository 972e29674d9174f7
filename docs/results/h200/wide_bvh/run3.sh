# Log 54 on the H200, run 3: `split` (app/octrace: the working tree, the
# top level binary through the binary walk, the meshes four-wide) and
# `near` (octrace-near: split with near.patch, the nearest child without
# the stack) against fc632c6 (octrace-base), --accel bvh, 5 rounds; images;
# the BVH's hard cases and accel_test of split on the GPU; the 1M and 10M
# fields at r = 0.01 with both structures (bench).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=80
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant base=BIN=$A --variant split=BIN=$B --variant near=BIN=build-gpu/octrace-near)
ab engine --scene .assets/2CylinderEngine.glb $S --accel bvh
ab balloon --scene .assets/balloon/scene.gltf $S --accel bvh
ab peer_bvh $P --accel bvh
ab s8000 --spheres 8000 --radius 0.1 $S --accel bvh
ab s488 --spheres 488 --radius 0.1 $S --accel bvh
AB_TIMEOUT=120 ab s1m --spheres 1000000 --radius 0.1 $S --accel bvh
for sc in "--scene tools/scenes/peer_field.json --spp 64 --rr-depth 1" "--spheres 8000 --radius 0.1 --spp 10" "--scene .assets/2CylinderEngine.glb --spp 10" "--scene .assets/balloon/scene.gltf --spp 10"; do
  for v in $A $B build-gpu/octrace-near; do timeout 30 $v render $sc --accel bvh --size 480x270 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "identity $sc: split $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical) near $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace-near.pfm && echo bit-identical)" >> $T
done
for v in $A $B build-gpu/octrace-near; do
  echo "$(basename $v) engine bvh: $($v render --scene .assets/2CylinderEngine.glb $S --accel bvh --pipeline-stats --json -q --out /tmp/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 600)" >> $T
done
export OCTRACE_TEST_DEVICE=gpu
suite accel_test 100
timeout 120 build-gpu/tests/hardcases_test --gtest_filter='Bvh/*' > $R/hardcases_bvh.txt 2>&1
echo "hardcases Bvh/* rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_bvh.txt | tr '\n' ' ')" >> $T
unset OCTRACE_TEST_DEVICE
timeout 130 $B bench --device gpu --accel octree,bvh --spheres 1000000,10000000 --radius 0.01 --csv $R/spheres_r001.csv > $R/spheres_r001.log 2>&1; echo "bench r=0.01 rc=$?" >> $T; tail -6 $R/spheres_r001.log >> $T
gpu_finish
