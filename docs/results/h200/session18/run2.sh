# Session 18 on the H200, run 2: the binary BVH walk's header in registers
# with 8-byte stack entries (expected.md): base (65a2908), W2 ((node, entry)
# stack), W4 ((first, count) stack, no early exit on pop; app/octrace, with
# the interrupt hook's checkpoint), and interrupt_test.
# Carried: .gl, .gpub (bin.tgz). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "W2=BIN=build-gpu/var/W2" --variant "W4=")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s128k_bvh $S --spheres 128000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s1m_r001_bvh $S --spheres 1000000 --radius 0.01 --accel bvh
suite interrupt_test 120
gpu_finish
