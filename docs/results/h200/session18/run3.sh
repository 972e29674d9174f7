# Session 18 on the H200, run 3: the kept form (W4, the interrupt hook's
# checkpoint) verified: the hard cases in four shards at once, accel_test,
# interrupt_test and the CUDA peer's build; then on an otherwise idle GPU
# the throwaway W6 against W4 (and 65a2908), the peer comparison with both
# structures, and the sparse sphere fields with both.
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
suite interrupt_test 120
echo "suites done at $(date -u +%T)" >> $T
V=(--variant "W4=" --variant "W6=BIN=build-gpu/var/W6" --variant "base=BIN=$A")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
AB_TIMEOUT=150 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1
echo "peer bvh rc=$?: $(grep -E 'x the peer|ratio|\| (CUDA|octrace)' $R/peer_bvh/peer_compare.md | tr '\n' ' ')" >> $T
timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer > $R/peer.log 2>&1
echo "peer octree rc=$?: $(grep -E 'x the peer|ratio|\| (CUDA|octrace)' $R/peer/peer_compare.md | tr '\n' ' ')" >> $T
timeout 60 $B bench --device gpu --accel octree,bvh --spheres 488,8000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1
echo "spheres rc=$?" >> $T; grep -E '^\| [0-9]' $R/spheres.log >> $T
gpu_finish
