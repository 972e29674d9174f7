# Prepared in session 30, for the next session with a GPU, after run 1: the
# GPU suites at HEAD (the host code changed; the shaders did not since
# 94fc5ce) and the peer side by side. Carried: .gl, .gpub, .assets, .peers.
source tools/gpu_run.sh
gpu_suites
peer peer_octree --accel octree
peer peer_bvh --accel bvh
gpu_finish
