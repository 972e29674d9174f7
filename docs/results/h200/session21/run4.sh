# Session 21 on the H200, run 4 (expected.md): the kept code (99d0867) -- the
# GPU suites while the peer builds, the peer side by side with both
# structures, `bench` of the sphere fields and the meshes, and 10M spheres
# with the fill off against the auto.
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
timeout 70 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer > $R/peer.log 2>&1
echo "peer octree rc=$?: $(grep -E '\| (CUDA|octrace)' $R/peer/peer_compare.md | tr '\n' ' ')" >> $T
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E '^\| [0-9]' $R/spheres.log >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/meshes.csv > $R/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E '^\| ' $R/meshes.log | tail -4 >> $T
timeout 150 python3 tools/ab_render.py --octrace $B --rounds 3 --render "$S --spheres 10000000 --radius 0.1 --accel bvh" --variant "auto=" --variant "off=-- --tail-fill off" --out $R/ab_s10m.md > $R/ab_s10m.log 2>&1
echo "s10m rc=$?: $(grep -E '^\| (auto|off) ' $R/ab_s10m.md | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> $T
gpu_finish
