#!/usr/bin/env bash
# render --json's times_ms.upload of two binaries, alternating, ROUNDS rounds
# after a warm-up each: the 1M field (r = 0.1) at 32x24, 1 spp, fp32 (or
# PRECISION), CPU device. Usage: upload_times.sh BEFORE AFTER [ROUNDS [PRECISION]]
set -u
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
rounds=${3:-7}
precision=${4:-fp32}
run() { "$1" render --device cpu --spheres 1000000 --radius 0.1 --size 32x24 --spp 1 --precision "$precision" --json -q -o /tmp/upload_times.png |
  python3 -c "import json,sys; print(json.load(sys.stdin)['times_ms']['upload'])"; }
run "$1" >/dev/null; run "$2" >/dev/null
for i in $(seq "$rounds"); do echo "before $(run "$1")"; echo "after $(run "$2")"; done |
  python3 -c "
import sys, statistics
v = {}
for line in sys.stdin:
    k, x = line.split(); v.setdefault(k, []).append(float(x))
b, a = statistics.median(v['before']), statistics.median(v['after'])
print(f'upload ms, median of {len(v[\"before\"])}: before {b:.1f} (min {min(v[\"before\"]):.1f}), after {a:.1f} (min {min(v[\"after\"]):.1f}), {a / b:.3f}x')"
rm -f /tmp/upload_times.png
