#!/usr/bin/env bash
# Time from a camera move in `octrace view` to the first pass that shows it
# (view --orbit-test: a scripted 1-degree orbit after each frame), at
# 1,000,000 spheres (r = 0.01), under Xvfb, on the CPU device unless
# DEVICE is set. Prints each run's median over its moves and the median of
# the runs.
#
#   tools/camera_move_latency.sh OCTRACE_BINARY [RUNS=5] [SIZE=400x225] [MOVES=10]
set -euo pipefail
bin=$1 runs=${2:-5} size=${3:-400x225} moves=${4:-10}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
medians=()
for ((i = 0; i < runs; i++)); do
  line=$(xvfb-run -a -s "-screen 0 1280x1024x24" "$bin" view --device "${DEVICE:-cpu}" --spheres 1000000 \
           --radius 0.01 --size "$size" --orbit-test "$moves" 2>&1 | grep "camera moves")
  m=$(sed -E 's/.*median ([0-9.]+) ms.*/\1/' <<<"$line")
  echo "run $((i + 1)): $line"
  medians+=("$m")
done
printf '%s\n' "${medians[@]}" | sort -g | awk '{a[NR]=$1} END {printf "median of %d runs: %.1f ms\n", NR, a[int((NR+1)/2)]}'
