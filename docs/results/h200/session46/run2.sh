# Session 46 run2: what fp16 costs the meshes in accuracy, beside run1's
# times: the balloon and the engine at the goals' settings (1200x800, 10
# spp, depth 50, octree) in fp32 and fp16 with the same sample seed, and
# fp32 with another (the noise floor); `octrace compare` of each against
# fp32, and render's count of non-finite samples. Expectations in
# expected.md (run2).
source tools/gpu_run.sh
for m in balloon:.assets/balloon/scene.gltf engine:.assets/2CylinderEngine.glb; do
  n=${m%%:*}; f=${m#*:}
  for v in fp32:"--precision fp32" fp16:"--precision fp16" fp32seed2:"--precision fp32 --sample-seed 2"; do
    l=${v%%:*}
    "$B" render $S --scene "$f" ${v#*:} --json -o "$R/${n}_$l.pfm" > "$R/${n}_$l.json" 2>&1
    echo "$n $l rc=$? nonfinite=$(grep -o '"nonfinite_samples": [0-9]*' "$R/${n}_$l.json")" >> "$T"
  done
  echo "$n fp16 against fp32: $("$B" compare "$R/${n}_fp16.pfm" "$R/${n}_fp32.pfm")" >> "$T"
  echo "$n fp32 seed 2 against fp32 (noise floor): $("$B" compare "$R/${n}_fp32seed2.pfm" "$R/${n}_fp32.pfm")" >> "$T"
  rm -f "$R"/*.pfm
done
gpu_finish
