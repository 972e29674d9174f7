# Session 42 run2: the copy leaves as the GPU's auto for meshes (e3ddf1d)
# against the old default tree (`--octree-refs 8`): device time on the four
# meshes (7 rounds), the whole process of a default render of the engine
# and the balloon, the images, `bench` of the meshes; then the GPU suites
# (the hard cases in four shards, accel_test, render_test's tail-queue and
# tree-settings cases; run3.sh, folded in to spend one machine start).
# Pack: tools/gpu_pack.sh (its COMMIT). Carried: .gl, .gpub, .assets.
# Expectations in expected.md (run2).
source tools/gpu_run.sh
V=(--variant "auto=" --variant "old=-- --octree-refs 8")
AB_ROUNDS=7 mesh_ab
AB_ROUNDS=7 AB_METRIC=wall ab engine_wall_10spp $S --scene .assets/2CylinderEngine.glb --accel octree
AB_ROUNDS=7 AB_METRIC=wall ab balloon_wall_10spp $S --scene .assets/balloon/scene.gltf --accel octree
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf "$R/grid.glb" "$R/grid400.glb"; do
  n=$(basename "$sc")
  for f in "" "--octree-refs 8"; do
    $B render $S --scene "$sc" --accel octree $f --json -o "$R/img_${f:+old}.pfm" > "$R/json.txt" 2>/dev/null
    echo "$n [${f:-auto}]: $(python3 -c "import json; o=json.load(open('$R/json.txt'))['octree']; print(o['max_refs'], 'refs, copy leaves', o['copy_leaf'], ':', round(o['bytes_per_primitive'], 1), 'bytes/triangle (first build', round(o['first_build_bytes_per_primitive'], 1), ')', round(o['build_ms']), 'ms build')")" >> "$T"
  done
  cmp -s "$R/img_.pfm" "$R/img_old.pfm" && echo "$n images identical" >> "$T" || \
    echo "$n images differ: $($B compare "$R/img_.pfm" "$R/img_old.pfm" 2>&1 | tr '\n' ' ')" >> "$T"
  rm -f "$R/img_.pfm" "$R/img_old.pfm"
done
rm -f "$R/grid.glb" "$R/grid400.glb"
bench_logged meshes 90 "rays/s$" --accel octree --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
gpu_suites
export OCTRACE_TEST_DEVICE=gpu
timeout 200 build-gpu/tests/render_test --gtest_filter='*TreeSettings*:OctreeLeaf.*:OctreeRefs.*' > "$R/render_test_autos.txt" 2>&1
echo "render_test autos rc=$? $(gtest_result "$R/render_test_autos.txt")" >> "$T"
gpu_finish
