# Session 48 run3: the leaf agreement's distance minimum over ordered
# integers (HEAD) against the float minimum (octrace-fmin:
# float_min.patch), the engine and the balloon, and their images.
# Expectations in expected.md (run3).
source tools/gpu_run.sh
V=(--variant "fmin=BIN=build-gpu/octrace-fmin" --variant "imin=")
ab engine_imin $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_imin $S --scene .assets/balloon/scene.gltf --accel octree
same_image "imin engine" build-gpu/octrace-fmin "$B" --size 1200x800 --spp 2 --depth 50 --device gpu --scene .assets/2CylinderEngine.glb --accel octree
same_image "imin balloon" build-gpu/octrace-fmin "$B" --size 1200x800 --spp 2 --depth 50 --device gpu --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
