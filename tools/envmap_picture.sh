#!/usr/bin/env bash
# The README's picture of the balloon under an HDRI: a glTF scene framed by
# octrace's own camera (--dump-scene writes it as JSON), its sky replaced by
# one of the CC0 HDRIs of Debian's blender-data (Greg Zaal, HDRI Haven),
# prepared by tools/envmap_prepare.py (DWAB -> ZIP, negative ringing -> 0).
#
#   tools/envmap_picture.sh OCTRACE GLTF HDRI OUT [SIZE] [SPP] [ROTATE]
#   e.g. tools/envmap_picture.sh build/app/octrace ../shared/scenes/balloon/scene.gltf forest \
#          docs/images/balloon_envmap_forest.png 320x240 32
#
# HDRI: a name in /usr/share/blender/datafiles/studiolights/world/ (forest,
# sunset, courtyard, ...). PYTHON: an interpreter with OpenEXR and numpy
# (default python3). Extra octrace flags: OCTRACE_FLAGS (e.g. "--device gpu").
set -euo pipefail
octrace=$1 gltf=$2 hdri=$3 out=$4 size=${5:-320x240} spp=${6:-32} rotate=${7:-0}
python=${PYTHON:-python3}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$python" "$here/envmap_prepare.py" "/usr/share/blender/datafiles/studiolights/world/$hdri.exr" "$work/$hdri.exr"
"$octrace" render --scene "$gltf" --size 8x6 --spp 1 --quiet --out "$work/frame.png" --dump-scene "$work/framed.json"
"$python" - "$work/framed.json" "$work/scene.json" "$hdri.exr" "$rotate" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["sky"] = {"type": "envmap", "file": sys.argv[3], "strength": 1, "rotate": float(sys.argv[4])}
json.dump(scene, open(sys.argv[2], "w"), indent=1)
PY
# shellcheck disable=SC2086
"$octrace" render --scene "$work/scene.json" --size "$size" --spp "$spp" ${OCTRACE_FLAGS:-} --out "$out"
