# Session 36, run 4: where the peer's lead lies now, by path length (log
# 51 measured it at 70d7e3b, 27.68 ms with the BVH; the code is at 20.5
# now): tools/peer/compare.py at depth 1 (camera rays alone), 2 and 3,
# both sides, with each structure. Expectations: expected.md ("run4.sh").
# Carried: .gl, .gpub, .peers.
source tools/gpu_run.sh
peer_build
for d in 1 2 3; do
  for a in bvh octree; do
    timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace "$B" --depth $d \
      --out "$R/peer_d${d}_$a" --octrace-args "--accel $a" > "$R/peer_d${d}_$a.log" 2>&1
    echo "depth $d $a rc=$?: $(grep -E '\| (CUDA|octrace)' "$R/peer_d${d}_$a/peer_compare.md" | tr '\n' ' ')" >> "$T"
  done
done
gpu_finish
