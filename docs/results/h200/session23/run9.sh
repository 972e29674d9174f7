# Session 23 on the H200, run 9 (expected.md): the queue at 3.84M entries
# instead of 2.8M, 1200x800, 10 spp. Carried: .gl, .gpub (run 5's bin.txz),
# .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "q28=" --variant "q29=OCTRACE_X_TAIL_LOG2=29")
AB_TIMEOUT=60 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=60 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=90 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
AB_TIMEOUT=60 ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
AB_TIMEOUT=60 ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
gpu_finish
