# Session 49 run7 (the session's final render code: the list pass as a
# shader of its own, camera_tiles.comp): the peer side by side and `bench`
# of the sphere rows again at this code, then the hard cases in eight
# shards of 300 s (the driver compiles the pipelines cold on a fresh
# machine: run 2 took about 4 s a case with eight shards at once), then
# the meshes' camera rays against their whole paths (device time, 5
# rounds), for the next lead. Expectations in expected.md (run7).
source tools/gpu_run.sh
peer_both
bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for k in 0 1 2 3 4 5 6 7; do
  GTEST_TOTAL_SHARDS=8 GTEST_SHARD_INDEX=$k timeout 300 build-gpu/tests/hardcases_test > "$R/hardcases_$k.txt" 2>&1 &
done
wait
for f in "$R"/hardcases_*.txt; do
  echo "$(basename "$f"): ok $(grep -c '^\[       OK \]' "$f"), failed $(grep -c '^\[  FAILED  \] .*(' "$f") $(gtest_result "$f")" >> "$T"
done
echo "hard cases done at $(date -u +%T)" >> "$T"
V=(--variant "depth50=" --variant "depth1=-- --depth 1" --variant "depth2=-- --depth 2")
ab engine_depth $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_depth $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
