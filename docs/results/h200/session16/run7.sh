# Session 16 on the H200, run 7: 10M spheres at r = 0.01, the octree at the
# default split budget and with `--octree-refs 16` (log 57), beside the BVH.
# Carried: .gl, .gpub (bin.tgz). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
for r in 8 16; do
  timeout 80 $B bench --device gpu --accel octree --spheres 10000000 --radius 0.01 --octree-refs $r \
    --csv "$R/s10m_refs$r.csv" > "$R/s10m_refs$r.log" 2>&1
  echo "octree-refs $r: $(grep 'ms (min' "$R/s10m_refs$r.log")" >> "$T"
done
gpu_finish
