#!/usr/bin/env bash
# Renders the same set of scenes with two octrace binaries and compares the
# linear images byte for byte: a refactoring that must not change any image
# (a new folder layout, a new seam) is checked with this.
#
#   tools/identity_check.sh OLD_BINARY NEW_BINARY [WORK_DIR]
#
# Scenes: the default rtiow scene, the golden tests' rtiow (60 spheres, r =
# 0.25, seed 7) and their four single-material scenes (tools/identity/*.json),
# each in fp32, fp16 and fp16-all, with the octree and brute force, on the CPU
# device (DEVICE=gpu for another). Prints one line per render and exits 1 if
# any image differs. NEW_FLAGS are passed to the new binary only (e.g.
# NEW_FLAGS="--nee off": the integrator without light sampling must render
# the old images of scenes with emitters bit for bit).
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2 work=${3:-$(mktemp -d)}
mkdir -p "$work/old" "$work/new"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}

scenes=("default|--size 160x90 --spp 4"
        "rtiow60|--spheres 60 --radius 0.25 --seed 7 --size 96x64 --spp 8")
for f in tools/identity/*.json; do
  scenes+=("$(basename "$f" .json)|--scene $f --size 96x64 --spp 8")
done

differ=0 total=0
for entry in "${scenes[@]}"; do
  name=${entry%%|*} flags=${entry#*|}
  for precision in fp32 fp16 fp16-all; do
    for accel in octree brute; do
      out="$name-$precision-$accel.pfm"
      # shellcheck disable=SC2086
      "$old" render --device "${DEVICE:-cpu}" --quiet $flags --precision $precision --accel $accel --out "$work/old/$out"
      # shellcheck disable=SC2086
      "$new" render --device "${DEVICE:-cpu}" --quiet $flags ${NEW_FLAGS:-} --precision $precision --accel $accel --out "$work/new/$out"
      total=$((total + 1))
      if cmp -s "$work/old/$out" "$work/new/$out"; then
        echo "identical  $out"
      else
        echo "DIFFERENT  $out"
        differ=$((differ + 1))
      fi
    done
  done
done
echo "$((total - differ)) of $total renders bit-identical"
[ "$differ" -eq 0 ]
