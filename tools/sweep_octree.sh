#!/usr/bin/env bash
# The sweep that chose the octree defaults: `octrace bench` over leaf sizes and
# depths, octree only, at the sphere counts of the goals. Writes one CSV per
# setting into OUT_DIR and prints a summary table (median device ms).
#   tools/sweep_octree.sh OCTRACE_BINARY OUT_DIR [extra bench flags...]
set -euo pipefail
bin=$1; out=$2; shift 2
mkdir -p "$out"
leaves=${LEAVES:-"2 4 8 16"}
depths=${DEPTHS:-"16"}
for d in $depths; do
  for k in $leaves; do
    "$bin" bench --quiet --accel octree --spheres 488,8000 --radius 0.1 --octree-leaf "$k" --octree-depth "$d" \
      --csv "$out/leaf${k}_depth${d}_r0.1.csv" "$@" >/dev/null
    "$bin" bench --quiet --accel octree --spheres 1000000 --radius 0.01 --octree-leaf "$k" --octree-depth "$d" \
      --csv "$out/leaf${k}_depth${d}_r0.01.csv" "$@" >/dev/null
  done
done
python3 - "$out" "$leaves" "$depths" <<'PY'
import csv, sys
out, leaves, depths = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
def rows(path):
    with open(path, newline="") as f:
        return {int(r["spheres"]): r for r in csv.DictReader(f)}
print("| leaf | depth | 488 r=0.1 ms | 8000 r=0.1 ms | 1M r=0.01 ms | bytes/sphere at 1M | build ms at 1M |")
print("|---:|---:|---:|---:|---:|---:|---:|")
for d in depths:
    for k in leaves:
        a = rows(f"{out}/leaf{k}_depth{d}_r0.1.csv")
        b = rows(f"{out}/leaf{k}_depth{d}_r0.01.csv")[1000000]
        print(f"| {k} | {d} | {float(a[488]['median_ms']):.2f} | {float(a[8000]['median_ms']):.2f} | "
              f"{float(b['median_ms']):.2f} | {float(b['bytes_per_sphere']):.1f} | {float(b['build_ms']):.0f} |")
PY
