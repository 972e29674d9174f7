# Session 18 on the H200, run 5: RenderSettings::nearest_child (held on CPU
# devices, pushed on GPUs: the loop of f55cf3c, its culling now a function):
# the hard cases (pushed) and accel_test (with the held form as a variant)
# four shards at once, then f55cf3c against it on the octree's scenes.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for k in 0 1 2 3; do
  GTEST_TOTAL_SHARDS=4 GTEST_SHARD_INDEX=$k timeout 240 build-gpu/tests/hardcases_test > $R/hardcases_$k.txt 2>&1 &
done
timeout 240 build-gpu/tests/accel_test > $R/accel_test.txt 2>&1 &
wait
for k in 0 1 2 3; do echo "hardcases shard $k: $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_$k.txt | tr '\n' ' ')" >> $T; done
echo "accel_test: $(grep -E '^\[  (PASSED|FAILED)' $R/accel_test.txt | tr '\n' ' ')" >> $T
echo "suites done at $(date -u +%T)" >> $T
tar czf "$OUT/results.tgz" -C /tmp res
V=(--variant "base=BIN=$A" --variant "new=")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
ab peer_octree $P --accel octree
ab s488_octree $S --spheres 488 --radius 0.1 --accel octree
ab engine $S --scene .assets/2CylinderEngine.glb --accel octree
gpu_finish
