# Session 21 on the H200, run 3 (expected.md), right after run 2: the GPU
# suites (hard cases in four shards, accel_test, render_test's tail-queue
# case) built from HEAD + all.patch (run 2's candidate) while the peer
# builds; `bench` of the goals' sphere fields and meshes at HEAD (the tail
# fill, log 64); the peer side by side with HEAD (both structures) and with
# var/all (the BVH).
# Carried: .gl, .gpub (bin.txz), .assets, .peers. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for k in 0 1 2 3; do
  GTEST_TOTAL_SHARDS=4 GTEST_SHARD_INDEX=$k timeout 240 build-gpu/tests/hardcases_test > $R/hardcases_$k.txt 2>&1 &
done
timeout 240 build-gpu/tests/accel_test > $R/accel_test.txt 2>&1 &
timeout 240 build-gpu/tests/render_test --gtest_filter='*TailQueue*' > $R/render_test.txt 2>&1 &
(cd .peers/karim && ./build.sh > $R/peer_build.log 2>&1) &
wait
for k in 0 1 2 3; do echo "hardcases shard $k: $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_$k.txt | tr '\n' ' ')" >> $T; done
echo "accel_test: $(grep -E '^\[  (PASSED|FAILED)' $R/accel_test.txt | tr '\n' ' ')" >> $T
echo "render_test tail: $(grep -E '^\[  (PASSED|FAILED)' $R/render_test.txt | tr '\n' ' ')" >> $T
echo "suites done at $(date -u +%T)" >> $T
timeout 70 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1
echo "peer bvh rc=$?: $(grep -E '\| (CUDA|octrace)' $R/peer_bvh/peer_compare.md | tr '\n' ' ')" >> $T
timeout 70 python3 tools/peer/compare.py --peer .peers/karim --octrace build-gpu/var/all --out $R/peer_bvh_all --octrace-args "--accel bvh" > $R/peer_bvh_all.log 2>&1
echo "peer bvh (var/all) rc=$?: $(grep -E '\| (CUDA|octrace)' $R/peer_bvh_all/peer_compare.md | tr '\n' ' ')" >> $T
timeout 70 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer > $R/peer.log 2>&1
echo "peer octree rc=$?: $(grep -E '\| (CUDA|octrace)' $R/peer/peer_compare.md | tr '\n' ' ')" >> $T
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E '^\| [0-9]' $R/spheres.log >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/meshes.csv > $R/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E '^\| ' $R/meshes.log | tail -6 >> $T
timeout 80 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 --csv $R/s10m.csv > $R/s10m.log 2>&1
echo "10M bvh rc=$?" >> $T; grep -E '^\| [0-9]' $R/s10m.log >> $T
gpu_finish
