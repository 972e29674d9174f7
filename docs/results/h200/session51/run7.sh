# Session 51, run 7: what the camera's list pass costs a render of 8,000
# and 488 spheres (r = 0.1) at the goals' settings with the octree, which
# log 146 took out of bench's timed renders (each reuses the lists of the
# warm-up's camera). Pack: as run6 (ae47877). Carry .gl, .gpub, .assets.
# Expectations: expected.md, run7.
source tools/gpu_run.sh
for n in 8000 488; do
  timeout 100 python3 tools/dispatch_table.py --octrace "$B" --render "$S --spheres $n --radius 0.1 --accel octree" --rounds 5 --out "$R/dispatch_$n.md" > /dev/null 2>&1
  echo "dispatch $n rc=$?: $(grep -E '^\| (camera_tiles|head|the passes) ' "$R/dispatch_$n.md" | cut -d'|' -f2,3,4 | tr '\n' ' ')" >> "$T"
done
cp "$R"/dispatch_*.md "$OUT/"
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
