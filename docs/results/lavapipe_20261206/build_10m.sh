# The 10M octree's build on lavapipe before and after log 126, one run each
# (2026-12-06 04:18 UTC; BEFORE = a002be6's tools/build.sh binary, AFTER =
# c0b54d6's); times_ms.accel_build of build_10m_before.json / _after.json.
export XDG_RUNTIME_DIR=/tmp
"$BEFORE" render --size 100x60 --spp 1 --device cpu --spheres 10000000 --radius 0.1 --accel octree --json -q -o /tmp/t10.pfm > build_10m_before.json
"$AFTER" render --size 100x60 --spp 1 --device cpu --spheres 10000000 --radius 0.1 --accel octree --json -q -o /tmp/t10.pfm > build_10m_after.json
