# Session 55, run 2: `bench` of the goals at HEAD (the render code of
# c720c39: the tail fetch's auto from 1,000 spheres with the octree, not
# yet in a `bench` of the goals), then whether Nsight Compute profiles a
# Vulkan dispatch on this machine (session 54's run 4, not run: no machine
# came): one kernel of the 8,000-sphere octree render, its speed-of-light
# and occupancy sections, 90 s at most. Pack: run 1's. Carry .gl, .gpub,
# .assets. Expectations: expected.md, run 2. After the bench: where the
# 8,000-sphere field's passes go with each structure, dispatch by dispatch
# (tools/dispatch_table.py), to say which stage holds the octree's excess.
source tools/gpu_run.sh
bench_goals
for a in octree bvh; do
  timeout 60 python3 tools/dispatch_table.py --octrace "$B" --rounds 5 --render "$S --spheres 8000 --radius 0.1 --accel $a" \
    --out "$OUT/dispatch_8000_$a.md" > "$R/dispatch_8000_$a.log" 2>&1
  echo "dispatch 8000 $a rc=$?: $(grep -E '^\| (head|whole|camera|tail [0-9]|sum|passes|rays)' "$OUT/dispatch_8000_$a.md" | cut -d'|' -f2-4 | tr '\n' ' ' | head -c 700)" >> "$T"
done
NCU=$(command -v ncu || ls /usr/local/cuda*/bin/ncu 2>/dev/null | head -1)
echo "ncu: ${NCU:-none}; $("${NCU:-true}" --version 2>&1 | tail -1)" >> "$T"
if [ -n "$NCU" ]; then
  timeout 90 "$NCU" --target-processes all --launch-skip 20 --launch-count 1 --section SpeedOfLight --section Occupancy \
    "$B" render $S --spheres 8000 --radius 0.1 --accel octree -q -o "$R/ncu.pfm" > "$OUT/ncu_8000_octree.txt" 2>&1
  echo "ncu rc=$? $(grep -c . "$OUT/ncu_8000_octree.txt") lines; $(grep -m4 -iE 'Duration|Compute \(SM\) Throughput|Memory Throughput|==ERROR|==WARNING|No kernels' "$OUT/ncu_8000_octree.txt" | tr '\n' ' ' | head -c 500)" >> "$T"
fi
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
