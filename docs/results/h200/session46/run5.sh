# Session 46 run5: where the balloon's fp16 gain (run4: 0.807x) lies: the
# same A/B at --depth 1 (camera rays and their shading) and --depth 3, and
# with the BVH at the goals' depth. Expectations in expected.md (run5).
source tools/gpu_run.sh
V=(--variant "fp32=-- --precision fp32" --variant "fp16=-- --precision fp16")
AB_ROUNDS=7
ab balloon_d1 --size 1200x800 --spp 10 --depth 1 --device gpu --scene .assets/balloon/scene.gltf --accel octree
ab balloon_d3 --size 1200x800 --spp 10 --depth 3 --device gpu --scene .assets/balloon/scene.gltf --accel octree
ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
gpu_finish
