#!/usr/bin/env bash
# Strong scaling on one host with several GPUs (issue 17): time to a fixed
# number of samples (1200x800, 1000 spp, depth 50) of the default scene and
# of the balloon, on 1 GPU (--device 0) and on K GPUs at once in one process
# (--device 0,1,...), median of RUNS runs after a warm-up. Builds nothing: run
# it on the GPU machine with a build carried there (like the single-GPU
# runs). MPI ranks (mpirun -np K): tools/mpi_scaling.sh.
#
#   tools/multi_gpu.sh OCTRACE_BINARY OUT_DIR [BALLOON.gltf] [RUNS]
set -euo pipefail
bin=$1 out=$2 balloon=${3:-} runs=${4:-5}
mkdir -p "$out"
date -u +"%Y-%m-%d %H:%M UTC" > "$out/date.txt"
"$bin" devices > "$out/devices.txt"
# The GPUs' indices (a software device the loader may also list is left out).
ids=($("$bin" devices --json | python3 -c "import json,sys; print(' '.join(str(d['index']) for d in json.load(sys.stdin) if not d['software']))"))
gpus=${#ids[@]}
echo "GPUs: $gpus (indices ${ids[*]})" | tee "$out/summary.txt"
[ "$gpus" -ge 1 ] || { echo "no GPU" >&2; exit 1; }
lists=("${ids[0]}")
for k in 2 4 8; do
  [ "$k" -le "$gpus" ] && lists+=("$(IFS=,; echo "${ids[*]:0:$k}")")
done
scenes=("default|")
[ -n "$balloon" ] && scenes+=("balloon|--scene $balloon")
echo "Render wall: from every device set up to the last pass done (octrace render --json times_ms.render_wall); process: the whole command; speedup and efficiency of the render wall, and of the process in brackets." >> "$out/summary.txt"
echo "| scene | GPUs | render wall s (median) | min | max | process s (median) | speedup | efficiency |" >> "$out/summary.txt"
echo "|---|---:|---:|---:|---:|---:|---:|---:|" >> "$out/summary.txt"
for entry in "${scenes[@]}"; do
  name=${entry%%|*} flags=${entry#*|}
  t1="" p1=""
  for list in "${lists[@]}"; do
    k=$(echo "$list" | tr ',' '\n' | wc -l)
    "$bin" render $flags --device "$list" --size 1200x800 --spp 1000 --quiet --out "$out/warm.png"  # warm-up
    : > "$out/$name-$k.jsonl"
    for r in $(seq "$runs"); do
      s=$(date +%s.%N)
      "$bin" render $flags --device "$list" --size 1200x800 --spp 1000 --json --out "$out/$name-$k.png" > "$out/run.json"
      e=$(date +%s.%N)
      python3 -c "import json,sys; j=json.load(open('$out/run.json')); j['process_s']=$e-$s; print(json.dumps(j))" \
        >> "$out/$name-$k.jsonl"
    done
    row=$(python3 - "$out/$name-$k.jsonl" "$k" "${t1:-0}" "${p1:-0}" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
k, t1, p1 = int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
wall = [r["times_ms"]["render_wall"] / 1000 for r in rows]
m, p = statistics.median(wall), statistics.median([r["process_s"] for r in rows])
t1, p1 = t1 or m, p1 or p
print(f"{m:.3f} {min(wall):.3f} {max(wall):.3f} {p:.3f} {t1 / m:.2f} {100 * t1 / (k * m):.1f} {p1 / p:.2f} {100 * p1 / (k * p):.1f}")
PY
)
    read -r med lo hi proc speed eff pspeed peff <<< "$row"
    [ -z "$t1" ] && t1=$med && p1=$proc
    echo "| $name | $k | $med | $lo | $hi | $proc | ${speed}x (${pspeed}x) | ${eff}% (${peff}%) |" | tee -a "$out/summary.txt"
  done
done
cat "$out/summary.txt"
