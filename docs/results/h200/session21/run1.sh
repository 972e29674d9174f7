# Session 21 on the H200, run 1 (expected.md): the tail fill (--tail-fill,
# 5798b2e) on the meshes with levels of step 1 against one tail, and on the
# sphere fields against levels without a fill; render_test's tail-queue case
# and layout_test on the GPU.
# Carried: .gl, .gpub (bin.tgz), .assets, .peers (not used). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
$B devices >> $T 2>&1
$B render $S --spheres 488 --radius 0.1 --json -q -o $R/x.png 2>/dev/null | grep -E '"tail_(depth|step|fill)"' | tr -d ' \n' >> $T; echo >> $T
V=(--variant "one=" --variant "s1off=-- --tail-step 1 --tail-fill off" --variant "s1auto=-- --tail-step 1" --variant "s1f64k=-- --tail-step 1 --tail-fill 65536" --variant "s1f1m=-- --tail-step 1 --tail-fill 1048576")
AB_TIMEOUT=80 ab balloon_octree $S --scene .assets/balloon/scene.gltf --accel octree
AB_TIMEOUT=80 ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
AB_TIMEOUT=90 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
AB_TIMEOUT=90 ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
V=(--variant "off=-- --tail-fill off" --variant "auto=" --variant "f64k=-- --tail-fill 65536" --variant "f1m=-- --tail-fill 1048576")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
AB_TIMEOUT=70 ab peer_bvh $P --accel bvh
AB_TIMEOUT=60 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=60 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=60 ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
AB_TIMEOUT=100 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
export OCTRACE_TEST_DEVICE=gpu; mkdir -p build-gpu/tests/tmp
suite_f() { timeout "$2" "build-gpu/tests/$1" --gtest_filter="$3" > "$R/$1.txt" 2>&1; echo "$1 ($3) rc=$? $(grep -E '^\[  (PASSED|FAILED)' "$R/$1.txt" | tr '\n' ' ')" >> "$T"; }
suite_f render_test 120 '*TailQueue*'
suite_f layout_test 60 '*'
gpu_finish
