# Session 46 run6: how much of each mesh's time at the goals' depth is the
# tail of its few longest paths: the engine and the balloon (octree, fp32)
# at depth 1, 2, 3, 6, 12 and 50, device time, alternating (one A/B of six
# variants each), and the rays each traces (render --json).
# Expectations in expected.md (run6).
source tools/gpu_run.sh
V=()
for d in 1 2 3 6 12 50; do V+=(--variant "d$d=-- --depth $d"); done
AB_ROUNDS=5
ab engine_depth --size 1200x800 --spp 10 --device gpu --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_depth --size 1200x800 --spp 10 --device gpu --scene .assets/balloon/scene.gltf --accel octree
for m in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  for d in 3 50; do
    echo "${m%%:*} depth $d rays: $("$B" render --size 1200x800 --spp 10 --device gpu --depth $d --scene "${m#*:}" --json -q -o "$R/r.pfm" | grep -o '"rays": [0-9]*')" >> "$T"
  done
done
rm -f "$R/r.pfm"
gpu_finish
