#!/usr/bin/env bash
# The mesh figures of docs/performance.md: the balloon ("Viva Balloon" by
# KevinAz61, CC-BY-4.0) and the 2CylinderEngine (Debian assimp-testmodels)
# at 1200x800, 10 spp, depth 50 (issue 11): render time, paths/s and rays/s,
# octree build and bytes per primitive, octree and brute force, fp32 and fp16.
#
#   tools/measure_meshes.sh OCTRACE_BINARY DEVICE OUT_DIR [BALLOON.gltf] [ENGINE.glb] [ACCELS]
#
# DEVICE: gpu or cpu. The scenes default to ../shared/scenes/balloon/scene.gltf
# and /usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb;
# on the GPU machine, which has neither, copy them into an ignored folder of
# the checkout (e.g. .assets/) and pass the paths. ACCELS defaults to
# octree,brute on a GPU and octree on the CPU device (brute force over 75,000
# triangles takes minutes per pass there).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$1 device=$2 out=$3
balloon=${4:-$here/../shared/scenes/balloon/scene.gltf}
engine=${5:-/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb}
accels=${6:-$([ "$device" = gpu ] && echo octree,brute || echo octree)}
mkdir -p "$out"
date -u +"%Y-%m-%d %H:%M UTC" > "$out/date.txt"
"$bin" devices > "$out/devices.txt"
for scene in "$balloon" "$engine"; do
  "$bin" render --device "$device" --scene "$scene" --size 1200x800 --spp 10 --quiet --json \
    --out "$out/$(basename "${scene%.*}" | tr 'A-Z' 'a-z').png" >> "$out/render.json"
done
"$bin" bench --device "$device" --scene "$balloon,$engine" --size 1200x800 --spp 10 --depth 50 \
  --accel "$accels" --precision fp32,fp16 --repeat 5 --csv "$out/bench_meshes.csv" \
  > "$out/bench_meshes.md" 2> "$out/bench_meshes.log"
cat "$out/bench_meshes.md"
