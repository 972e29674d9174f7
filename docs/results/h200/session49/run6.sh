# Session 49 run6 (the machine of run5, a38bd69's pack): the peer side by
# side at the session's final render code (the camera tiles' auto of
# run5; the peer's scene has 492 spheres, under either bound). As sent:
source tools/gpu_run.sh; peer_both; gpu_finish
