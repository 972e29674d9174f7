# Session 54, run 4: render_test's tail-fetch case at 401dcc2 (the BVH's
# field of 4,196 spheres under the auto again, the octree's of 1,100; run
# 3 ran it with the BVH's at 8,100), and whether Nsight Compute profiles
# a Vulkan dispatch on this machine (not tried before): one kernel of the
# 8,000-sphere octree render, its speed-of-light section. Pack:
# tools/gpu_pack.sh at 401dcc2. Carry .gl, .gpub, .assets.
# Expectations: expected.md, run 4.
source tools/gpu_run.sh
render_cases '*TailFetch*' 200
NCU=$(command -v ncu || ls /usr/local/cuda*/bin/ncu 2>/dev/null | head -1)
echo "ncu: ${NCU:-none}" >> "$T"
if [ -n "$NCU" ]; then
  timeout 90 "$NCU" --target-processes all --launch-skip 20 --launch-count 1 --section SpeedOfLight --section Occupancy \
    "$B" render $S --spheres 8000 --radius 0.1 --accel octree -q -o "$R/ncu.pfm" > "$OUT/ncu_8000_octree.txt" 2>&1
  echo "ncu rc=$? $(grep -c . "$OUT/ncu_8000_octree.txt") lines; $(grep -m3 -iE 'Duration|Compute \(SM\) Throughput|Memory Throughput|==ERROR|==WARNING' "$OUT/ncu_8000_octree.txt" | tr '\n' ' ' | head -c 400)" >> "$T"
fi
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
