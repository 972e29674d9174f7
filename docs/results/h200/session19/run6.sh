# Session 19 on the H200, run 6 (expected.md): throwaway N0.5 (the BVH's
# node cost 0.5: leaves of one sphere) against the kept code, --accel bvh,
# and `bench` of both at 8,000 spheres.
# Carried: .gl, .gpub (bin.tgz). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "kept=" --variant "N05=BIN=build-gpu/var/N0.5")
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
ab peer_bvh $P --accel bvh
ab s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=200 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
for b in $B build-gpu/var/N0.5; do
  timeout 60 $b bench --device gpu --accel bvh --spheres 8000 --radius 0.1 > $R/bench_$(basename $b).log 2>&1
  echo "bench 8000 $b rc=$?: $(grep -E '^\| [0-9]' $R/bench_$(basename $b).log)" >> $T
done
gpu_finish
