#!/usr/bin/env bash
# The GPU figures of docs/performance.md and docs/precision.md in one command:
# device list, the bench of octree against brute force, the precision bench,
# the million-sphere scene, the effects bench and the accuracy report. Run on
# the GPU machine with a build of octrace for it:
#   tools/gpu_measure.sh OCTRACE_BINARY OUT_DIR
set -euo pipefail
bin=$1; out=$2
mkdir -p "$out"
"$bin" devices | tee "$out/devices.txt"
date -u +"%Y-%m-%d %H:%M UTC" > "$out/date.txt"
"$bin" bench --device gpu --budget 30 --csv "$out/bench.csv" > "$out/bench.md" 2> "$out/bench.log"
"$bin" bench --device gpu --accel octree --spheres 1000000 --radius 0.01 --csv "$out/bench_1m.csv" \
  > "$out/bench_1m.md" 2>> "$out/bench.log"
"$bin" bench --device gpu --accel octree,brute --spheres 488,8000 --radius 0.1 --precision fp32,fp16,fp16-all \
  --budget 30 --csv "$out/bench_precision.csv" > "$out/bench_precision.md" 2>> "$out/bench.log"
"$bin" bench --device gpu --family rtiow,lambertian,metal,glass,emissive,pinhole --precision fp32,fp16 \
  --csv "$out/bench_effects.csv" > "$out/bench_effects.md" 2>> "$out/bench.log"
if command -v python3 >/dev/null; then
  python3 "$(dirname "$0")/accuracy.py" --octrace "$bin" --device gpu --size 400x225 --study-size 1200x800 \
    --out "$out/accuracy" > "$out/accuracy.log" 2>&1 || echo "accuracy failed: see accuracy.log"
fi
cat "$out/bench.md" "$out/bench_1m.md" "$out/bench_precision.md" "$out/bench_effects.md"
