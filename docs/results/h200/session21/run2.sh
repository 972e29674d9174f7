# Session 21 on the H200, run 2 (expected.md): throwaway v1-v5 and all (the
# patches beside this script) against HEAD's code, image identity on the GPU,
# and render_test's tail-queue case (the meshes' auto) on the GPU.
# Carried: .gl, .gpub (bin.tgz with var/v1..v5, var/all), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
for a in bvh octree; do
  $B render $P --accel $a --spp 8 -q -o $R/k.pfm
  for v in v1 v2 v3 v4 v5 all; do build-gpu/var/$v render $P --accel $a --spp 8 -q -o $R/v.pfm; cmp -s $R/k.pfm $R/v.pfm && echo "$v identical peer $a" >> $T || echo "$v DIFFERENT peer $a" >> $T; done
done
$B render $S --scene .assets/2CylinderEngine.glb --accel bvh --spp 2 -q -o $R/k.pfm
build-gpu/var/all render $S --scene .assets/2CylinderEngine.glb --accel bvh --spp 2 -q -o $R/v.pfm; cmp -s $R/k.pfm $R/v.pfm && echo "all identical engine bvh" >> $T || echo "all DIFFERENT engine bvh" >> $T
rm -f $R/*.pfm
V=(--variant "base=")
for v in v1 v2 v3 v4 v5 all; do V+=(--variant "$v=BIN=build-gpu/var/$v"); done
AB_TIMEOUT=110 ab peer_bvh $P --accel bvh
AB_TIMEOUT=60 ab peer_bvh_d1 $P --accel bvh --depth 1
AB_TIMEOUT=60 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
V=(--variant "base=")
for v in v1 v3 v4 v5 all; do V+=(--variant "$v=BIN=build-gpu/var/$v"); done
AB_TIMEOUT=100 ab peer_octree $P --accel octree
AB_TIMEOUT=60 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
V=(--variant "base=" --variant "all=BIN=build-gpu/var/all")
AB_TIMEOUT=60 ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
export OCTRACE_TEST_DEVICE=gpu; mkdir -p build-gpu/tests/tmp
timeout 120 build-gpu/tests/render_test --gtest_filter='*TailQueue*' > $R/render_test.txt 2>&1; echo "render_test TailQueue rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/render_test.txt | tr '\n' ' ')" >> $T
gpu_finish
