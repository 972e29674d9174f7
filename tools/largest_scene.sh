#!/usr/bin/env bash
# The largest scene: renders the rtiow field with N small spheres (default
# 100,000,000, the H100 target of issue 13; docs/performance.md "Scenes
# larger than one buffer" has lavapipe's 30,000,000) at a small size and few
# samples, and records what it took: the process's peak resident memory
# (/usr/bin/time -v), the device's peak memory where nvidia-smi can say,
# the times octrace reports (scene, octree build, upload, pipeline, render)
# and into how many buffers the scene was split.
#
# usage: tools/largest_scene.sh [BINARY] [SPHERES] [RADIUS] [OUT_DIR]
#   BINARY   octrace (default build/app/octrace; -DOCTRACE_WINDOW=OFF is fine)
#   SPHERES  small spheres (default 100000000)
#   RADIUS   their radius (default 0.0005: the field is 20 x 20 units, so
#            100M spheres have cells of 0.002; the generator refuses a
#            radius whose spheres would not fit their cells)
#   OUT_DIR  where the report and the image go (default results/largest_scene)
# Writes OUT_DIR/largest_scene_SPHERES.txt (device, date, commit, command,
# octrace's summary, peak memory) and OUT_DIR/largest_scene_SPHERES.png.
set -euo pipefail

bin=${1:-build/app/octrace}
spheres=${2:-100000000}
radius=${3:-0.0005}
out_dir=${4:-results/largest_scene}
size=${SIZE:-400x225}
spp=${SPP:-2}

mkdir -p "$out_dir"
report="$out_dir/largest_scene_$spheres.txt"
image="$out_dir/largest_scene_$spheres.png"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
cmd=("$bin" render --device "${DEVICE:-auto}" --spheres "$spheres" --radius "$radius" --size "$size" --spp "$spp" -o "$image")

# The device's memory in use, sampled twice a second while octrace runs
# (NVIDIA only; nothing is written without nvidia-smi).
gpu_log="$out_dir/.gpu_memory_$spheres"
: >"$gpu_log"
sampler=""
if command -v nvidia-smi >/dev/null; then
  (while true; do nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits >>"$gpu_log" 2>/dev/null || true; sleep 0.5; done) &
  sampler=$!
fi

{
  echo "# tools/largest_scene.sh $*"
  echo "# date:    $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "# commit:  $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "# host:    $(nproc) cores, $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo) memory"
  echo "# command: ${cmd[*]}"
} >"$report"

status=0
/usr/bin/time -v "${cmd[@]}" >>"$report" 2>"$out_dir/.time_$spheres" || status=$?
[ -n "$sampler" ] && kill "$sampler" 2>/dev/null || true
grep -v "^\s*\(Average\|Exit status\|Socket\|Signals\|Swaps\|File system\|Page size\|Voluntary\|Involuntary\|Minor\|Major\|Percent\)" \
  "$out_dir/.time_$spheres" >>"$report" || true
if [ -s "$gpu_log" ]; then
  echo "peak device memory in use (nvidia-smi, sampled every 0.5 s): $(sort -n "$gpu_log" | tail -1) MiB" >>"$report"
fi
rm -f "$gpu_log" "$out_dir/.time_$spheres"
echo "exit status: $status" >>"$report"
cat "$report"
exit "$status"
