# Session 19 on the H200, run 4 (expected.md): throwaways N2 and N3 (the
# BVH's node cost 2 and 3) against 70183fd with --accel bvh; then `bench` of
# 10M spheres, the BVH's spheres in the tree's order and in the scene's.
# Carried: .gl, .gpub (bin.tgz). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "kept=" --variant "N2=BIN=build-gpu/var/N2.0" --variant "N3=BIN=build-gpu/var/N3.0")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
for o in auto scene; do
  timeout 150 $B bench --device gpu --accel bvh --bvh-sphere-order $o --spheres 10000000 --radius 0.1 --csv $R/s10m_$o.csv > $R/s10m_$o.log 2>&1
  echo "10M bvh order $o rc=$?" >> $T; grep -E '^\| [0-9]' $R/s10m_$o.log >> $T
done
timeout 150 $B bench --device gpu --accel octree --spheres 10000000 --radius 0.1 --csv $R/s10m_octree.csv > $R/s10m_octree.log 2>&1
echo "10M octree rc=$?" >> $T; grep -E '^\| [0-9]' $R/s10m_octree.log >> $T
gpu_finish
