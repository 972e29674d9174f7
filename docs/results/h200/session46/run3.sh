# Session 46 run3: why fp16 is faster on the balloon (run1: 0.80x), and
# what it does to the peer's comparison: the path-tracing pipeline's
# statistics (registers, workgroup memory) of the balloon and the engine in
# fp32 and fp16; the peer built and compared side by side with `--accel
# bvh` in fp32 (the goal's figure) and fp16, and the octree in fp16.
# Carried: .gl, .gpub, .assets, .peers/karim. Expectations in expected.md
# (run3).
source tools/gpu_run.sh
for p in fp32 fp16; do
  pipeline_stats "balloon $p" "$B" $S --scene .assets/balloon/scene.gltf --precision $p
  pipeline_stats "engine $p" "$B" $S --scene .assets/2CylinderEngine.glb --precision $p
done
peer_build
peer peer_bvh --accel bvh
peer peer_bvh_fp16 --accel bvh --precision fp16
peer peer_octree_fp16 --accel octree --precision fp16
gpu_finish
