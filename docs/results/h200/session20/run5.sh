# Session 20 on the H200, run 5 (expected.md): tail levels (--tail-step N,
# afa0264) and throwaway G (geometric levels) against the auto (depth 2,
# one tail), over the goals' scenes; render_test's tail-queue case on the GPU.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
G=build-gpu/var/G
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
V=(--variant "auto=" --variant "s1=-- --tail-step 1" --variant "s2=-- --tail-step 2" --variant "s4=-- --tail-step 4" --variant "G1=BIN=$G -- --tail-step 1" --variant "G2=BIN=$G -- --tail-step 2")
AB_TIMEOUT=150 ab peer_bvh $P --accel bvh
AB_TIMEOUT=150 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
V=(--variant "auto=" --variant "t4=-- --tail-depth 4" --variant "s1=-- --tail-step 1" --variant "s2=-- --tail-step 2" --variant "G1=BIN=$G -- --tail-step 1")
AB_TIMEOUT=150 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=150 ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
AB_TIMEOUT=150 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
V=(--variant "auto=" --variant "s1=-- --tail-step 1" --variant "s2=-- --tail-step 2" --variant "G1=BIN=$G -- --tail-step 1")
AB_TIMEOUT=120 ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
AB_TIMEOUT=120 ab balloon_octree $S --scene .assets/balloon/scene.gltf --accel octree
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
export OCTRACE_TEST_DEVICE=gpu; mkdir -p build-gpu/tests/tmp
suite_f() { timeout "$2" "build-gpu/tests/$1" --gtest_filter="$3" > "$R/$1.txt" 2>&1; echo "$1 ($3) rc=$? $(grep -E '^\[  (PASSED|FAILED)' "$R/$1.txt" | tr '\n' ' ')" >> "$T"; }
suite_f render_test 120 '*TailQueue*'
suite_f layout_test 60 '*'
gpu_finish
