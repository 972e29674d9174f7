# Session 20 on the H200, run 3 (expected.md): the peer side by side at
# depth 1 and 2 with the BVH; the tail depth and the head's sample lanes
# swept on the peer's scene and 8,000 spheres with the BVH.
# Carried: .gl, .gpub (bin.tgz), .peers. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
(cd .peers/karim && ./build.sh > $R/peer_build.log 2>&1) &
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64 --accel bvh"
V=(--variant "auto=" --variant "t1=-- --tail-depth 1" --variant "t3=-- --tail-depth 3" --variant "toff=-- --tail-depth off")
AB_TIMEOUT=150 ab peer_tail $P
V=(--variant "auto=" --variant "l1=-- --sample-lanes 1" --variant "l2=-- --sample-lanes 2" --variant "l8=-- --sample-lanes 8")
AB_TIMEOUT=150 ab peer_lanes $P
V=(--variant "auto=" --variant "t1=-- --tail-depth 1" --variant "t3=-- --tail-depth 3" --variant "l1=-- --sample-lanes 1" --variant "l8=-- --sample-lanes 8")
AB_TIMEOUT=150 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
wait
for d in 1 2; do
  timeout 100 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --depth $d --out $R/peer_d$d --octrace-args "--accel bvh" > $R/peer_d$d.log 2>&1
  echo "peer bvh depth $d rc=$?: $(grep -E '\| (CUDA|octrace)' $R/peer_d$d/peer_compare.md | tr '\n' ' ')" >> $T
done
gpu_finish
