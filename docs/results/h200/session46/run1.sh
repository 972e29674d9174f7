# Session 46 run1: `bench` of the glTF goal's scenes (the balloon, the
# engine) with both structures and both precisions, with this session's
# bench (paths/s and rays/s at the median time, no longer the last run's).
# No render code changed since session 42. Pack: tools/gpu_pack.sh of
# this session's commit (its COMMIT). Carried: .gl, .gpub, .assets.
# Expectations in expected.md (run1).
source tools/gpu_run.sh
bench_logged meshes 240 "rays/s$" --accel octree,bvh --precision fp32,fp16 \
  --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
gpu_finish
