#!/usr/bin/env bash
# The 1M field's octree with the surface cells at reference budgets 2, 4 and
# 8 (the default), against no cells: the tree's size and what a query does
# (`--walk-stats`, per query), on the CPU device (counts, not times).
# Usage: docs/results/lavapipe_20261206b/surface_refs.sh [OCTRACE]
bin=${1:-build/app/octrace}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
echo "| cells, refs | nodes | references | bytes a sphere | sphere tests a query | nodes a query | box tests a query |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for m in "off 8" "on 2" "on 4" "on 8"; do
  set -- $m
  "$bin" render --device cpu --spheres 1000000 --radius 0.1 --octree-surfaces "$1" --octree-refs "$2" \
    --size 96x64 --spp 1 --depth 8 --walk-stats --json -q -o /tmp/surface_refs.png |
    python3 -c "
import json, sys
d = json.load(sys.stdin); o = d['octree']; w = d['walk']; q = w['queries']
print(f\"| $1, $2 | {o['nodes']} | {o['refs']} | {o['bytes_per_primitive']:.1f} | {w['primitives']/q:.2f} | {w['nodes']/q:.2f} | {w['boxes']/q:.2f} |\")"
done
rm -f /tmp/surface_refs.png
