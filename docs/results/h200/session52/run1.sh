# Session 52, run 1: session 51's next1.sh (it had no device time
# left for it). Pack: tools/gpu_pack.sh (HEAD; no probe). Carry .gl,
# .gpub, .assets. Expectations (session 51, written before): the hard
# cases 340/340 (log 151 changes only when the camera's lists are made);
# render_test's dispatch-time case passes (it now resets and renders
# again); the list pass (`camera_tiles`) 0.3-0.45 ms of 8,000 spheres'
# octree render and 0.03-0.06 ms of 488's (run7.sh's tables); `bench` of
# the goals with the list pass timed again (log 151): 8,000 spheres'
# octree near session 49's 5.56 ms (ratio to the BVH near 1.33), 488's
# rows about 3% above session 51's run 5 (1.81 / 1.32 ms), the meshes as
# run 5 (the engine 8.55 ms, 1.97e9; the balloon 2.64 ms).
source tools/gpu_run.sh
for n in 8000 488; do
  timeout 100 python3 tools/dispatch_table.py --octrace "$B" --render "$S --spheres $n --radius 0.1 --accel octree" --rounds 5 --out "$R/dispatch_$n.md" > /dev/null 2>&1
  echo "dispatch $n rc=$?: $(grep -E '^\| (camera_tiles|head|the passes) ' "$R/dispatch_$n.md" | cut -d'|' -f2,3,4 | tr '\n' ' ')" >> "$T"
done
bench_goals
render_cases '*DispatchTimes*:*CameraTiles*' 200
hardcases_shards 8 240
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
