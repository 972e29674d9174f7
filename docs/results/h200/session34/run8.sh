# Session 34, run 8 (the command given on the warm machine right after run
# 7, with the pack of run 7): lane_sample's entries 64 / 128 / 192 on the
# meshes (the engine with the octree, the balloon with the BVH).
source tools/gpu_run.sh; E=build-gpu/octrace-entries; V=(--variant "e128=" --variant "e64=BIN=$E OCTRACE_LANE_ENTRIES=64" --variant "e192=BIN=$E OCTRACE_LANE_ENTRIES=192"); AB_TIMEOUT=60 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree; AB_TIMEOUT=60 ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh; gpu_finish
