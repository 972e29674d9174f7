# Session 20 on the H200, run 1 (expected.md): e993f32's suites on the GPU
# (the hard cases in four shards, accel_test) while the CUDA peer builds;
# then the peer side by side with both structures.
# Carried: .gl, .gpub (bin.tgz), .peers. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for k in 0 1 2 3; do
  GTEST_TOTAL_SHARDS=4 GTEST_SHARD_INDEX=$k timeout 300 build-gpu/tests/hardcases_test > $R/hardcases_$k.txt 2>&1 &
done
timeout 300 build-gpu/tests/accel_test > $R/accel_test.txt 2>&1 &
(cd .peers/karim && ./build.sh > $R/peer_build.log 2>&1) &
wait
for k in 0 1 2 3; do echo "hardcases shard $k: $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_$k.txt | tr '\n' ' ')" >> $T; done
echo "accel_test: $(grep -E '^\[  (PASSED|FAILED)' $R/accel_test.txt | tr '\n' ' ')" >> $T
echo "suites done at $(date -u +%T)" >> $T
timeout 100 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1
echo "peer bvh rc=$?: $(grep -E '\| (CUDA|octrace)' $R/peer_bvh/peer_compare.md | tr '\n' ' ')" >> $T
timeout 100 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer > $R/peer.log 2>&1
echo "peer octree rc=$?: $(grep -E '\| (CUDA|octrace)' $R/peer/peer_compare.md | tr '\n' ' ')" >> $T
gpu_finish
