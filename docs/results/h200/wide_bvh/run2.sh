# Log 54 on the H200, run 2: run 1 found the four-wide BVH slower on the
# sparse sphere fields and faster on the meshes. Which level gains: one
# binary of the working tree with env_width.patch (children per node from
# OCTRACE_BVH_TOP and OCTRACE_BVH_MESH, 4 if unset; a throwaway switch)
# against fc632c6 (octrace-base, the binary walk): w44 (both levels four
# wide), w24 (the top level binary, the meshes four wide), w22 (binary
# trees through the new walk: its cost without the width). Then the BVH's
# hard cases and accel_test on the GPU, with w44 and w24.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=100
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant base=BIN=$A --variant "w44=BIN=$B OCTRACE_BVH_TOP=4 OCTRACE_BVH_MESH=4"
   --variant "w24=BIN=$B OCTRACE_BVH_TOP=2 OCTRACE_BVH_MESH=4" --variant "w22=BIN=$B OCTRACE_BVH_TOP=2 OCTRACE_BVH_MESH=2")
ab peer_bvh $P --accel bvh
ab s488 --spheres 488 --radius 0.1 $S --accel bvh
ab s8000 --spheres 8000 --radius 0.1 $S --accel bvh
ab engine --scene .assets/2CylinderEngine.glb $S --accel bvh
ab balloon --scene .assets/balloon/scene.gltf $S --accel bvh
AB_TIMEOUT=150 ab s1m --spheres 1000000 --radius 0.1 $S --accel bvh
export OCTRACE_TEST_DEVICE=gpu
suite accel_test 120
for w in 4 2; do
  OCTRACE_BVH_TOP=$w timeout 150 build-gpu/tests/hardcases_test --gtest_filter='Bvh/*' > $R/hardcases_bvh_top$w.txt 2>&1
  echo "hardcases Bvh/* top $w mesh 4 rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_bvh_top$w.txt | tr '\n' ' ')" >> $T
done
gpu_finish
