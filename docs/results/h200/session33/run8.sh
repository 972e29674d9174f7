# Run 8 (typed on the warm machine, 14:06 UTC): `bench` at 10M spheres, the BVH. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh; timeout 200 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 > $OUT/spheres10m.log 2>&1; echo "bench 10M rc=$?" >> $T; grep -E " ms" $OUT/spheres10m.log | grep -v '^#' | tail -3 >> $T; gpu_finish
