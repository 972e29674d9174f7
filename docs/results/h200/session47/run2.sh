# Session 47 run2: the GPU suites at the subgroup stage's code (the hard
# cases in four shards, accel_test, render_test's tail-queue case, which
# now checks the stage bit for bit), then `bench` of the meshes (the glTF
# goal's rays/s). Expectations in expected.md (run2).
source tools/gpu_run.sh
gpu_suites
bench_logged meshes 120 "rays/s$" --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
gpu_finish
