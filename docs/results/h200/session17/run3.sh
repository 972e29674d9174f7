# Session 17 on the H200, run 3: the code with pipeline robustness off by
# default (log 58). First, with the GPU shared: the whole hard-case suite in
# four shards at once, accel_test, cli_test's robust-buffers case, and the
# CUDA peer's build; then, on an otherwise idle GPU, the peer comparison
# (octree and BVH), the sphere series and the meshes' rays/s.
# Carried: .gl, .gpub (bin.tgz), .assets, .peers. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for k in 0 1 2 3; do
  GTEST_TOTAL_SHARDS=4 GTEST_SHARD_INDEX=$k timeout 320 build-gpu/tests/hardcases_test > $R/hardcases_$k.txt 2>&1 &
done
timeout 320 build-gpu/tests/accel_test > $R/accel_test.txt 2>&1 &
(cd .peers/karim && ./build.sh > $R/peer_build.log 2>&1) &
wait
for k in 0 1 2 3; do echo "hardcases shard $k: $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_$k.txt | tr '\n' ' ')" >> $T; done
echo "accel_test: $(grep -E '^\[  (PASSED|FAILED)' $R/accel_test.txt | tr '\n' ' ')" >> $T
timeout 60 build-gpu/tests/cli_test --gtest_filter="Cli.RobustBuffers*" > $R/cli_robust.txt 2>&1
echo "cli_test robust rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/cli_robust.txt | tr '\n' ' ')" >> $T
echo "suites done at $(date -u +%T)" >> $T
timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer > $R/peer.log 2>&1
echo "peer octree rc=$?: $(grep -E 'x the peer|ratio|\| (CUDA|octrace)' $R/peer/peer_compare.md | tr '\n' ' ')" >> $T
timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1
echo "peer bvh rc=$?: $(grep -E 'x the peer|ratio|\| (CUDA|octrace)' $R/peer_bvh/peer_compare.md | tr '\n' ' ')" >> $T
timeout 120 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1
echo "spheres rc=$?" >> $T; grep -E '^\| [0-9]' $R/spheres.log >> $T
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf --scene .assets/2CylinderEngine.glb --csv $R/meshes.csv > $R/meshes.log 2>&1
echo "meshes rc=$?" >> $T; grep -E '^\| ' $R/meshes.log | tail -4 >> $T
gpu_finish
