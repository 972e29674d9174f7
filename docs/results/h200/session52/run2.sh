# Session 52, run 2: session 51's next1.sh (it had no device time left
# for it): the list pass in the dispatch tables at 8,000 and 488
# spheres, `bench` of the goals with the list pass timed again (log
# 151), render_test's camera-tile and dispatch-time cases on the GPU.
# Pack: run 1's (its HEAD is the code). Carry .gl, .gpub, .assets.
# Expectations: expected.md, run 2 (session 51's, copied there).
source tools/gpu_run.sh
for n in 8000 488; do
  timeout 100 python3 tools/dispatch_table.py --octrace "$B" --render "$S --spheres $n --radius 0.1 --accel octree" --rounds 5 --out "$R/dispatch_$n.md" > /dev/null 2>&1
  echo "dispatch $n rc=$?: $(grep -E '^\| (camera_tiles|head|the passes) ' "$R/dispatch_$n.md" | cut -d'|' -f2,3,4 | tr '\n' ' ')" >> "$T"
done
bench_goals
render_cases '*DispatchTimes*:*CameraTiles*' 150
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
