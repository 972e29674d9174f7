# Session 38, run 1b: the command run on the warm machine right after run1.sh
# (the same pack), as it ran (one line there; split here for reading):
# the 1M octree field before/after at depth 8 and 50, and --walk-stats of
# both. Output: run1b/diff.txt.
source tools/gpu_run.sh >/dev/null 2>&1
for d in 8 50; do
  for v in base new; do
    bin=$B; [ $v = base ] && bin=$A
    "$bin" render --size 1200x800 --spp 10 --depth $d --device gpu --spheres 1000000 --radius 0.1 --accel octree -q -o $R/d${d}_$v.pfm
  done
  python3 -c "
import numpy as np,sys
def pfm(p):
    f=open(p,'rb'); f.readline(); w,h=map(int,f.readline().split()); sc=float(f.readline()); return np.frombuffer(f.read(),dtype='<f4' if sc<0 else '>f4')
a=pfm('$R/d${d}_base.pfm'); b=pfm('$R/d${d}_new.pfm'); d=a!=b
print('depth $d base vs new: %d of %d values differ, max %.3g, means %.6g / %.6g' % (d.sum(), a.size, abs(a-b).max(), a.mean(), b.mean()))
" 2>&1 | tee -a $OUT/diff.txt
done
"$B" render $S --spheres 1000000 --radius 0.1 --accel octree --walk-stats -o $R/w.pfm 2>&1 | grep -E "^(octree|walk|times)" | tee -a $OUT/diff.txt
"$A" render $S --spheres 1000000 --radius 0.1 --accel octree --walk-stats -o $R/w.pfm 2>&1 | grep -E "^(octree|walk|times)" | tee -a $OUT/diff.txt
