# Session 29 on the H200, run 2 (expected.md): the GPU suites at 94fc5ce
# while the peer builds; with an argument N, the hard cases and accel_test
# of f6d93d3 + sstack.patch (tests/*_sst) with OCTRACE_SSTACK=N beside them;
# the peer side by side with both structures; --walk-stats on NVIDIA for
# every family. Carried: .gl, .gpub (bin.txz), .assets, .peers.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
N=${1:-}
if [ -n "$N" ]; then
  (export OCTRACE_TEST_DEVICE=gpu OCTRACE_SSTACK=$N
   for k in 0 1; do GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=$k timeout 300 build-gpu/tests/hardcases_test_sst > $R/sst_hardcases_$k.txt 2>&1 & done
   timeout 300 build-gpu/tests/accel_test_sst > $R/sst_accel_test.txt 2>&1 &
   wait) &
  SST=$!
fi
gpu_suites
if [ -n "$N" ]; then
  wait $SST
  for k in 0 1; do echo "sst N=$N hardcases shard $k: $(gtest_result $R/sst_hardcases_$k.txt)" >> $T; done
  echo "sst N=$N accel_test: $(gtest_result $R/sst_accel_test.txt)" >> $T
fi
peer peer_bvh --accel bvh
peer peer_octree
timeout 150 python3 tools/walk_stats.py --octrace $B --render "--device gpu --size 1200x800 --spp 2 --depth 50" \
  --scene "the peer's scene (488 spheres of radius 0.2, 1920x1080, 2 spp, roulette from 1)=--scene tools/scenes/peer_field.json --size 1920x1080 --rr-depth 1" \
  --scene "488 spheres of radius 0.1=--spheres 488 --radius 0.1" --scene "8,000 spheres of radius 0.1=--spheres 8000 --radius 0.1" \
  --scene "1M spheres of radius 0.1=--spheres 1000000 --radius 0.1" \
  --scene "balloon=--scene .assets/balloon/scene.gltf" --scene "engine=--scene .assets/2CylinderEngine.glb" --out $OUT/walk_stats.md > $R/walk_stats.log 2>&1
echo "walk_stats rc=$?" >> $T
gpu_finish
