# Session 19 on the H200, run 3 (expected.md): the kept code's suites (the
# hard cases in four shards, accel_test, render_test's reconfigure case,
# cli_test's BVH cases) while the CUDA peer builds; then the peer side by
# side with both structures.
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
timeout 120 build-gpu/tests/render_test --gtest_filter='*Reconfigure*' > $R/render_test.txt 2>&1
echo "render_test reconfigure rc=$?: $(grep -E '^\[  (PASSED|FAILED)' $R/render_test.txt | tr '\n' ' ')" >> $T
timeout 120 build-gpu/tests/cli_test --gtest_filter='*Bvh*:*BadInput*' > $R/cli_test.txt 2>&1
echo "cli_test bvh rc=$?: $(grep -E '^\[  (PASSED|FAILED)' $R/cli_test.txt | tr '\n' ' ')" >> $T
echo "suites done at $(date -u +%T)" >> $T
timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1
echo "peer bvh rc=$?: $(grep -E 'x the peer|ratio|\| (CUDA|octrace)' $R/peer_bvh/peer_compare.md | tr '\n' ' ')" >> $T
timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer > $R/peer.log 2>&1
echo "peer octree rc=$?: $(grep -E 'x the peer|ratio|\| (CUDA|octrace)' $R/peer/peer_compare.md | tr '\n' ' ')" >> $T
gpu_finish
