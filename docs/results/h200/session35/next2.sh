# Prepared in session 35 for the next session, then run in session 35
# itself as run 8 (18:02 UTC, its last GPU time; log 117):
# log 117's queue past the 4,194,240 entries that 65535 workgroups cover.
# NVIDIA's driver allows 2^31 - 1 workgroups along x; a probe
# (tail_groups_env.patch: OCTRACE_TAIL_GROUPS) lets the queue take up to
# half a dispatch's paths: 6.0M and 7.68M (half of 1200x800 x 16). Pack:
# tools/gpu_pack.sh tailgroups=docs/results/h200/session35/tail_groups_env.patch.
# Expectations: expected.md ("next2.sh"). Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
S16="--size 1200x800 --spp 16 --depth 50 --device gpu"
C=build-gpu/octrace-tailgroups
V=(--variant "auto=" --variant "q6m=BIN=$C OCTRACE_TAIL_GROUPS=94000" --variant "q768=BIN=$C OCTRACE_TAIL_GROUPS=120000")
ab g16_s8000_bvh $S16 --spheres 8000 --radius 0.1 --accel bvh
ab g16_s8000_octree $S16 --spheres 8000 --radius 0.1 --accel octree
AB_TIMEOUT=120 ab g16_s1m_bvh $S16 --spheres 1000000 --radius 0.1 --accel bvh
ab g16_engine_octree $S16 --scene .assets/2CylinderEngine.glb --accel octree
ab g16_balloon_bvh $S16 --scene .assets/balloon/scene.gltf --accel bvh
AB_TIMEOUT=120 ab g_peer_bvh $P --accel bvh
same_image s8000_16 $B $C $S16 --spheres 8000 --radius 0.1 --accel bvh
gpu_finish
