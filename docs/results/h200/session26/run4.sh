# Session 26 on the H200, run 4 (expected.md): the GPU suites while the
# peer builds, then the peer side by side with both structures, at
# bd2f5fc's code. Carried: .gl, .gpub (bin.txz), .peers.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
gpu_suites
peer peer_bvh --accel bvh
peer peer_octree
gpu_finish
