# Session 41 run4: the whole process of `render` with run3's autos (the
# engine's tree built twice) against the old autos given as flags, at 10
# and 1000 spp. Pack: run3's. Carried: .gl, .gpub, .assets. Expectations in
# expected.md (run4).
source tools/gpu_run.sh
V=(--variant "auto=" --variant "old=-- --octree-refs 8 --octree-leaf 10")
AB_METRIC=wall AB_TIMEOUT=200 ab engine_wall_10spp $S --scene .assets/2CylinderEngine.glb --accel octree
AB_METRIC=wall AB_TIMEOUT=250 ab engine_wall_1000spp --size 1200x800 --spp 1000 --depth 50 --device gpu --scene .assets/2CylinderEngine.glb --accel octree
AB_METRIC=wall AB_TIMEOUT=200 ab balloon_wall_10spp $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
