# Session 42 run4: `bench` of the meshes with both structures at the new
# defaults (e3ddf1d: copy leaves), for the octree/BVH ratios on the meshes.
# Pack: run2's. Carried: .gl, .gpub, .assets. Expectations in expected.md (run4).
source tools/gpu_run.sh
bench_logged meshes 120 "rays/s$" --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
gpu_finish
