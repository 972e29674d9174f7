# Session 52, run 4: the kept tail fetch (log 152) timed: A/B of its auto
# against `--tail-fetch off` on both meshes with both structures, the
# engine's image, and `bench` of the goals at HEAD. Pack: run 3's.
# Carry .gl, .gpub, .assets. Expectations: expected.md, run 4.
source tools/gpu_run.sh
ENG="$S --scene .assets/2CylinderEngine.glb"
"$B" render $ENG --accel octree --tail-fetch off -q -o "$R/off.pfm"; "$B" render $ENG --accel octree -q -o "$R/auto.pfm"
cmp -s "$R/off.pfm" "$R/auto.pfm" && echo "engine fetch auto vs off identical" >> "$T" || echo "engine fetch auto vs off DIFFERENT" >> "$T"
V=(--variant "off=-- --tail-fetch off" --variant auto=)
ab engine_octree $ENG --accel octree
ab engine_bvh $ENG --accel bvh
ab balloon_octree $S --scene .assets/balloon/scene.gltf --accel octree
ab balloon_bvh $S --scene .assets/balloon/scene.gltf --accel bvh
bench_goals
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
