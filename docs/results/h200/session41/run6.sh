# Session 41 run6: the octree autos for scenes with triangles on a GPU with
# the leaf-20 tree made coarser from the first instead of built again (log
# 133) against the old autos given as flags: device time on four meshes,
# the whole process at 10 spp, the images, the GPU suites (bench left out:
# the device budget left; ab_render gives rays/s).
# Pack: tools/gpu_pack.sh (its COMMIT). Carried: .gl, .gpub, .assets.
# Expectations in expected.md (run6).
source tools/gpu_run.sh
python3 tools/make_grid_glb.py 708 "$R/grid.glb" > /dev/null
python3 tools/make_grid_glb.py 187 "$R/grid400.glb" 400 > /dev/null
gpu_suites
export OCTRACE_TEST_DEVICE=gpu
timeout 200 build-gpu/tests/render_test --gtest_filter='*TreeSettings*:OctreeLeaf.*:OctreeRefs.*' > "$R/render_test_autos.txt" 2>&1
echo "render_test autos rc=$? $(gtest_result "$R/render_test_autos.txt")" >> "$T"
unset OCTRACE_TEST_DEVICE
V=(--variant "auto=" --variant "old=-- --octree-refs 8 --octree-leaf 10")
AB_TIMEOUT=200 ab engine $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=200 ab balloon $S --scene .assets/balloon/scene.gltf --accel octree
AB_TIMEOUT=200 ab sheet $S --scene "$R/grid.glb" --accel octree
AB_TIMEOUT=200 ab grid400 $S --scene "$R/grid400.glb" --accel octree
AB_ROUNDS=7 AB_METRIC=wall AB_TIMEOUT=200 ab engine_wall_10spp $S --scene .assets/2CylinderEngine.glb --accel octree
AB_ROUNDS=7 AB_METRIC=wall AB_TIMEOUT=200 ab balloon_wall_10spp $S --scene .assets/balloon/scene.gltf --accel octree
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf "$R/grid.glb" "$R/grid400.glb"; do
  n=$(basename "$sc")
  for f in "" "--octree-refs 8 --octree-leaf 10"; do
    $B render $S --scene "$sc" --accel octree $f --json -o "$R/img_${n}_${f:+old}.pfm" > "$R/json.txt" 2>/dev/null
    echo "$n [${f:-auto}]: $(python3 -c "import json; o=json.load(open('$R/json.txt'))['octree']; print(o['leaf_size'], 'leaf', o['max_refs'], 'refs:', round(o['bytes_per_primitive'], 1), 'bytes/triangle (as built', round(o['first_build_bytes_per_primitive'], 1), 'bytes)', round(o['build_ms']), 'ms build')")" >> "$T"
  done
  cmp -s "$R/img_${n}_.pfm" "$R/img_${n}_old.pfm" && echo "$n images identical" >> "$T" || \
    echo "$n images differ: $($B compare "$R/img_${n}_.pfm" "$R/img_${n}_old.pfm" 2>&1 | tr '\n' ' ')" >> "$T"
  rm -f "$R/img_${n}_.pfm" "$R/img_${n}_old.pfm"
done
rm -f "$R/grid.glb" "$R/grid400.glb"
gpu_finish
