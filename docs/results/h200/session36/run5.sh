# Session 36, run 5: run 4 put the peer's lead in the first two segments
# (depth 1: 7.99 against 5.97 ms, BVH; the increment to depth 2: 7.02
# against 5.25; beyond depth 2 octrace is faster). At depth <= 2 the
# queue takes nothing, so the staged dispatch's values (16 bytes a
# sample, written by the head, read by the sum) and the sum's 96 bytes a
# pixel of accumulation state are all it adds to the whole paths, which
# add their samples in registers (the peer's shape). Whole paths
# (`--tail-depth off`) side by side with the peer at depth 1, 2 and 50.
# Expectations: expected.md ("run5.sh"). Carried: .gl, .gpub, .peers.
source tools/gpu_run.sh
peer_build
for d in 1 2 50; do
  timeout 90 python3 tools/peer/compare.py --peer .peers/karim --octrace "$B" --depth $d \
    --out "$R/peer_d${d}_whole" --octrace-args "--accel bvh --tail-depth off" > "$R/peer_d${d}_whole.log" 2>&1
  echo "depth $d bvh whole rc=$?: $(grep -E '\| (CUDA|octrace)' "$R/peer_d${d}_whole/peer_compare.md" | tr '\n' ' ')" >> "$T"
done
gpu_finish
