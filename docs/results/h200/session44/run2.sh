# Session 44 run2: the GPU suites at this session's code (the CLI's checks
# and validate_settings' octree limits: renderer/render/settings.cpp,
# renderer/scene/scene.cpp), then `bench` of the goals' sphere fields and
# meshes and the peer's comparison with both structures: the goals' latest
# figures at HEAD. Pack: tools/gpu_pack.sh (its COMMIT). Carried: .gl,
# .gpub, .assets, .peers/karim. Expectations in expected.md (run2).
source tools/gpu_run.sh
gpu_suites
peer_both
bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
bench_logged meshes 90 "rays/s$" --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
gpu_finish
