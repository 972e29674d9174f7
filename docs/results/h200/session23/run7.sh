# Session 23 on the H200, run 7 (expected.md): 8 samples per dispatch on
# the peer's scene. Carried: .gl, .gpub (run 5's bin.txz), .assets.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
V=(--variant "d7=" --variant "d8=OCTRACE_X_TAIL_LOG2=29 OCTRACE_X_TAIL_MAX=8")
AB_TIMEOUT=100 ab peer_bvh $P --accel bvh
AB_TIMEOUT=100 ab peer_octree $P --accel octree
gpu_finish
