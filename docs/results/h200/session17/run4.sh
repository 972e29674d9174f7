# Session 17 on the H200, run 4: the machine code without the bounds checks
# (run 2's dumps of the robustness-off variant, unpacked here with
# tools/nvidia_sass.py unpack into .gpub/sass_norobust_*), and the sphere
# fields run 3 left out (128,000 and 10M at r = 0.1, 10M at r = 0.01), at
# the kept code of d168363 (run 3's bin.tgz).
# Carried: .gl, .gpub. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
for a in bvh octree; do
  python3 tools/nvidia_sass.py disasm .gpub/sass_norobust_$a --nvdisasm /usr/local/cuda/bin/nvdisasm >> $T
  mkdir -p $R/sass_norobust_$a; cp .gpub/sass_norobust_$a/*.sass $R/sass_norobust_$a/
done
timeout 100 $B bench --device gpu --accel octree,bvh --spheres 128000,10000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1
echo "spheres r=0.1 rc=$?" >> $T; grep -E '^\| [0-9]' $R/spheres.log >> $T
timeout 60 $B bench --device gpu --accel octree,bvh --spheres 10000000 --radius 0.01 --csv $R/s10m.csv > $R/s10m.log 2>&1
echo "10M r=0.01 rc=$?" >> $T; grep -E '^\| [0-9]' $R/s10m.log >> $T
gpu_finish
