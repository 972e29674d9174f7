# Session 23 on the H200, run 2 (expected.md): the kept VT2 (triangle_hit)
# against 9132513 and the GPU suites with it; `bench` of the meshes; 10M
# spheres: `render` in one batch, `bench` without its warm-up, the memory
# clock. Carried: .gl, .gpub (bin.txz: app/octrace = VT2, octrace-base,
# var/x1, tests), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
gpu_suites
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for a in bvh octree; do
  $A render $S --scene $sc --accel $a --spp 2 -q -o $R/k.pfm; $B render $S --scene $sc --accel $a --spp 2 -q -o $R/v.pfm
  cmp -s $R/k.pfm $R/v.pfm && echo "vt2 identical $a $sc" >> $T || echo "vt2 DIFFERENT $a $sc" >> $T
done; done
rm -f $R/*.pfm
V=(--variant "base=BIN=$A" --variant "vt2=")
AB_TIMEOUT=60 ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
AB_TIMEOUT=60 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
timeout 150 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $R/bench_meshes.txt 2>&1
echo "bench meshes rc=$?" >> $T; grep -E '^\|' $R/bench_meshes.txt | tail -5 >> $T
clk() { nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,utilization.gpu,pstate --format=csv,noheader -lms 20 > "$R/clk_$1.csv" & CP=$!; }
r10m() {  # NAME BIN [ENV]: one 10M render, its times and the clocks
  clk $1; sleep 0.5
  env ${3:-X=1} $2 render $S --spheres 10000000 --radius 0.1 --accel bvh --json -q -o $R/r10m.png > $R/render10m_$1.json 2> $R/render10m_$1.err
  sleep 0.5; kill $CP
  echo "render 10M $1: $(python3 -c "import json; j=json.load(open('$R/render10m_$1.json')); print(round(j['times_ms']['render'],1), 'ms')")" >> $T
}
r10m batched $B
r10m one build-gpu/var/x1 OCTRACE_X_ONE_BATCH=1
clk bench; sleep 0.5
timeout 100 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 --warmup 0 --repeat 5 > $R/bench10m_nowarm.txt 2>&1
sleep 0.5; kill $CP
echo "bench 10M, no warm-up, 5 runs: $(grep -E '^\| 10000000' $R/bench10m_nowarm.txt)" >> $T
rm -f $R/r10m.png
python3 - "$R" >> $T <<'PY'
import sys, csv, glob
for f in sorted(glob.glob(f"{sys.argv[1]}/clk_*.csv")):
    rows = [[c.strip() for c in r] for r in csv.reader(open(f)) if len(r) >= 6]
    busy = [r for r in rows if r[4] != "0 %"]
    print(f.split("/")[-1], len(rows), "samples,", len(busy), "busy; busy (sm, mem, pstate) first 6:",
          [(r[1], r[2], r[5]) for r in busy[:6]], "distinct mem clocks while busy:", sorted({r[2] for r in busy}))
PY
gpu_finish
