# Session 23 on the H200, run 1 (expected.md): VT2 again with more rounds;
# --tail-depth 2/3/4 on the meshes; the SM clock through a 10M `render`
# and `bench`. Carried: .gl, .gpub (bin.txz with var/vt), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for a in bvh octree; do
  $B render $S --scene $sc --accel $a --spp 2 -q -o $R/k.pfm; build-gpu/var/vt render $S --scene $sc --accel $a --spp 2 -q -o $R/v.pfm
  cmp -s $R/k.pfm $R/v.pfm && echo "vt identical $a $sc" >> $T || echo "vt DIFFERENT $a $sc" >> $T
done; done
rm -f $R/*.pfm
abn() {  # ab with ROUNDS rounds
  local name=$1 rounds=$2; shift 2
  timeout ${AB_TIMEOUT:-90} python3 tools/ab_render.py --octrace "$B" --rounds $rounds --render "$*" "${V[@]}" --out "$R/ab_$name.md" > "$R/ab_$name.log" 2>&1
  echo "$name rc=$?: $(grep -E '^\| [a-z0-9]+ ' "$R/ab_$name.md" | grep -v variant | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> "$T"
}
V=(--variant "base=" --variant "vt=BIN=build-gpu/var/vt")
AB_TIMEOUT=80 abn balloon_bvh 15 $S --scene .assets/balloon/scene.gltf --accel bvh
AB_TIMEOUT=80 abn balloon_octree 15 $S --scene .assets/balloon/scene.gltf --accel octree
AB_TIMEOUT=80 abn engine_bvh 9 $S --scene .assets/2CylinderEngine.glb --accel bvh
AB_TIMEOUT=80 abn engine_octree 9 $S --scene .assets/2CylinderEngine.glb --accel octree
V=(--variant "d2=" --variant "d3=-- --tail-depth 3" --variant "d4=-- --tail-depth 4")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do for a in bvh octree; do
  AB_TIMEOUT=80 abn depth_${sc%%:*}_$a 7 $S --scene ${sc#*:} --accel $a
done; done
echo "ab done at $(date -u +%T)" >> $T
clk() { nvidia-smi --query-gpu=timestamp,clocks.sm,power.draw,utilization.gpu --format=csv,noheader -lms 20 > "$R/clk_$1.csv" & CP=$!; }
clk render; sleep 1
$B render $S --spheres 10000000 --radius 0.1 --accel bvh --json -q -o $R/r10m.png > $R/render10m.json 2> $R/render10m.err
sleep 1; kill $CP
clk bench; sleep 1
timeout 120 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 > $R/bench10m.txt 2>&1
sleep 1; kill $CP
rm -f $R/r10m.png
python3 - "$R" >> $T <<'PY'
import sys, json, csv
R = sys.argv[1]
j = json.load(open(f"{R}/render10m.json"))
print("render 10M times_ms:", {k: round(v, 1) for k, v in j.get("times_ms", {}).items() if isinstance(v, (int, float))})
for name in ("render", "bench"):
    rows = [r for r in csv.reader(open(f"{R}/clk_{name}.csv")) if len(r) >= 4]
    busy = [r for r in rows if r[3].strip() not in ("0 %",)]
    clocks = [int(r[1].split()[0]) for r in busy]
    print(f"{name}: {len(rows)} samples, {len(busy)} with the GPU busy; SM MHz while busy: first {clocks[:8]} median {sorted(clocks)[len(clocks)//2] if clocks else None} max {max(clocks) if clocks else None}")
PY
tail -4 $R/bench10m.txt >> $T
gpu_finish
