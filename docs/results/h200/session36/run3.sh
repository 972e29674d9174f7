# Session 36, run 3: log 117's queue from a user's side (left by session
# 35): longer renders of 8,000 spheres, whole process and device time,
# HEAD (ca148ff's code) against the old queue (session 35's
# old_queue.patch, in the pack as build-gpu/octrace-old); the balloon as
# a scene whose queue never filled. Expectations: expected.md
# ("run3.sh"). Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
L="--size 1200x800 --spp 1024 --depth 50 --device gpu"
V=(--variant "new=" --variant "old=BIN=build-gpu/octrace-old")
AB_METRIC=wall AB_TIMEOUT=150 ab wall1024_s8000_bvh $L --spheres 8000 --radius 0.1 --accel bvh
AB_METRIC=wall AB_TIMEOUT=150 ab wall1024_s8000_octree $L --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=150 ab dev1024_s8000_bvh $L --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=150 ab dev1024_s8000_octree $L --spheres 8000 --radius 0.1 --accel octree
AB_METRIC=wall AB_TIMEOUT=150 ab wall1024_balloon_bvh $L --scene .assets/balloon/scene.gltf --accel bvh
same_image s8000_1024 "$B" build-gpu/octrace-old $L --spheres 8000 --radius 0.1 --accel bvh
gpu_finish
