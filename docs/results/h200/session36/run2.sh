# Session 36, run 2: the probe of spatial splits over spheres
# (sphere_splits_probe.patch, in the pack as build-gpu/octrace-spheresplit;
# expectations: expected.md, "run2.sh"). The probe's forced form: spatial
# splits along y only, a side may take every sphere, the spatial
# candidate's SAH cost weighed by 0.2, up to 4 references a sphere: the
# tree the binned SAH never builds on its own (lavapipe's walk counts: 1M
# spheres 102 -> 18 sphere tests a query). Carried: .gl, .gpub.
source tools/gpu_run.sh
P=build-gpu/octrace-spheresplit
Y="BIN=$P OCTRACE_SPATIAL_ALL=1 OCTRACE_SPATIAL_Y=1 OCTRACE_SPATIAL_F=0.2 OCTRACE_SPHERE_REFS=4"
V=(--variant "base=" --variant "ysplit=$Y")
AB_TIMEOUT=300 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
# The image: the probe's tree against HEAD's, bit for bit.
env OCTRACE_SPATIAL_ALL=1 OCTRACE_SPATIAL_Y=1 OCTRACE_SPATIAL_F=0.2 OCTRACE_SPHERE_REFS=4 \
  "$P" render $S --spheres 1000000 --radius 0.1 --accel bvh --walk-stats --json -o "$R/y.pfm" > "$R/y.json" 2> "$R/y.err"
"$B" render $S --spheres 1000000 --radius 0.1 --accel bvh --walk-stats --json -o "$R/b.pfm" > "$R/b.json" 2> "$R/b.err"
cmp -s "$R/y.pfm" "$R/b.pfm" && echo "s1m identical (probe vs base)" >> "$T" || echo "s1m DIFFERENT (probe vs base)" >> "$T"
python3 - "$R/b.json" "$R/y.json" >> "$T" <<'PY'
import json, sys
for f in sys.argv[1:]:
    j = json.load(open(f)); b = j["bvh"]; w = j["walk"]; q = w["queries"]
    print(f.split("/")[-1], "build_ms", round(b["build_ms"]), "nodes", b["nodes"], "refs", b["refs"], "order", b["sphere_order"],
          "nodes/q %.2f boxes/q %.2f spheres/q %.2f" % (w["nodes"] / q, w["boxes"] / q, w["primitives"] / q))
PY
rm -f "$R/y.pfm" "$R/b.pfm"
gpu_finish
