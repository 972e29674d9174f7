# Session 35, run 7: log 117's queue (HEAD) against a71283e's (the probe
# `old`: old_queue.patch), at 16 samples a dispatch (1200x800) and at the
# goals' settings; images of both identical; render_test's tail-queue case
# with the new queue on the GPU. Expectations: expected.md. Carried: .gl,
# .gpub, .assets.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
S16="--size 1200x800 --spp 16 --depth 50 --device gpu"
V=(--variant "new=" --variant "old=BIN=build-gpu/octrace-old")
ab q16_s8000_bvh $S16 --spheres 8000 --radius 0.1 --accel bvh
ab q16_s8000_octree $S16 --spheres 8000 --radius 0.1 --accel octree
ab q16_engine_octree $S16 --scene .assets/2CylinderEngine.glb --accel octree
ab q16_balloon_bvh $S16 --scene .assets/balloon/scene.gltf --accel bvh
ab q10_s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=120 ab peer_bvh $P --accel bvh
same_image s8000_16 $B build-gpu/octrace-old $S16 --spheres 8000 --radius 0.1 --accel bvh
same_image engine_16 $B build-gpu/octrace-old $S16 --scene .assets/2CylinderEngine.glb --accel octree
mkdir -p build-gpu/tests/tmp
OCTRACE_TEST_DEVICE=gpu timeout 120 build-gpu/tests/render_test --gtest_filter='*TailQueue*' > $R/render_tail.txt 2>&1
echo "render_test tail rc=$? $(gtest_result $R/render_tail.txt)" >> $T
gpu_finish
