# Prepared in session 31 (no GPU lent there), for the next session with one:
# log 105's probe, the BVH build's parallel depth on the GPU machine's 16
# cores (build-gpu/octrace-pdepth reads OCTRACE_BVH_PDEPTH; the default is
# 2, kBvhParallelDepth), times_ms.accel_build of the engine and of a
# 1M-triangle sheet; and the whole process's peak memory at each depth.
# Expectations: docs/results/lavapipe_20261205d/expected.md (log 105).
# Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
P=build-gpu/octrace-pdepth
python3 tools/make_grid_glb.py 708 $R/sheet.glb > /dev/null 2>&1 || echo "sheet: make_grid_glb failed" >> $T
for scene in .assets/2CylinderEngine.glb $R/sheet.glb; do
  n=$(basename $scene .glb)
  timeout 150 python3 tools/ab_render.py --octrace $P --rounds 5 --metric accel_build \
    --render "--scene $scene --size 64x36 --spp 1 --accel bvh --device gpu" \
    --variant "d2=OCTRACE_BVH_PDEPTH=2" --variant "d0=OCTRACE_BVH_PDEPTH=0" --variant "d3=OCTRACE_BVH_PDEPTH=3" \
    --variant "d4=OCTRACE_BVH_PDEPTH=4" --variant "d5=OCTRACE_BVH_PDEPTH=5" --variant "d6=OCTRACE_BVH_PDEPTH=6" \
    --out $R/ab_build_$n.md > $R/ab_build_$n.log 2>&1
  echo "build $n rc=$?: $(grep -E '^\| d[0-9] ' $R/ab_build_$n.md | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> $T
  for d in 0 2 3 4 5 6; do  # peak memory (ru_maxrss of the child) at each depth
    OCTRACE_BVH_PDEPTH=$d python3 -c "import resource,subprocess,sys; subprocess.run(sys.argv[1:]); print('$n d=$d maxrss', resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, 'KB')" \
      $P render --scene $scene --size 64x36 --spp 1 --accel bvh --device gpu -q -o $R/x.pfm >> $T 2>&1
  done
done
rm -f $R/sheet.glb $R/x.pfm
gpu_finish
