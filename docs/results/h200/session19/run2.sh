# Session 19 on the H200, run 2 (expected.md): the kept code's sphere order
# (auto = the tree's on a GPU, and --bvh-sphere-order scene) against D and
# e2ada62 with --accel bvh; then `bench` of the sphere fields, both structures.
# Carried: .gl, .gpub (bin.tgz). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "D=BIN=build-gpu/var/D" --variant "scene=-- --bvh-sphere-order scene" --variant "tree=")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s128k_bvh $S --spheres 128000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1
echo "spheres rc=$?" >> $T; grep -E '^\| [0-9]' $R/spheres.log >> $T
gpu_finish
