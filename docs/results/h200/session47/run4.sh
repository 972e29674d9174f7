# Session 47 run4: the subgroup stage's new auto (fill and threshold 4
# paths a resident warp: 33,792 on an H100) against off, the engine and
# the balloon (octree), 5 rounds, device time; `bench` of the meshes (the
# glTF goal's rays/s); the GPU suites (run2's, merged in); last, if the
# device time holds, the sphere fields off against auto.
# Expectations in expected.md (run4, run2).
source tools/gpu_run.sh
V=(--variant "off=-- --tail-subgroup off" --variant "auto=")
AB_ROUNDS=5
ab engine_f $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_f $S --scene .assets/balloon/scene.gltf --accel octree
bench_logged meshes 120 "rays/s$" --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
gpu_suites
ab s488_f $S --spheres 488 --radius 0.1 --accel octree
ab s8000_f $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=120 ab s1m_f $S --spheres 1000000 --radius 0.1 --accel octree
gpu_finish
