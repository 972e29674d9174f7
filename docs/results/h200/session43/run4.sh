# Session 43 run4: what the meshes' goals cost in memory: `bench` of the
# balloon and the engine at the defaults (octree and BVH), and the octree
# with the budget given (`--octree-refs 12`, 16 and 24: no copy leaves,
# over issue 11's 48 bytes a triangle; the user's trade, README).
# Pack: run2's (90f376e: HEAD's render code). Carried: .gl, .gpub, .assets.
# Expectations in expected.md (run4).
source tools/gpu_run.sh
M=.assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
bench_logged meshes 90 "rays/s$" --accel octree,bvh --scene $M
for r in 12 16 24; do
  bench_logged meshes_refs$r 90 "rays/s$" --accel octree --scene $M --octree-refs $r
done
for f in $OUT/meshes*.log; do echo "$(basename $f): $(grep -E '^\| (scene|2Cyl)' $f | cut -d'|' -f2,5,7,11,12,14 | tr '\n' ' ')" >> $T; done
gpu_finish
