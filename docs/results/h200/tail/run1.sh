# Where the time of a path goes by bounce (before any tail change): `bench`
# at bounce limits 1..50 on the meshes and on the 488-sphere field, so the
# share of the passes spent after bounce k is the difference. Carried: .gl,
# .gpub (bin.tgz of the commit in COMMIT), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
for d in 1 2 3 4 6 8 12 20 50; do
  timeout 60 $B bench --device gpu -q --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --accel octree --depth $d --repeat 5 > $R/mesh_d$d.md 2>&1
  echo "meshes depth $d rc=$?: $(grep -E '^\| [^-]' $R/mesh_d$d.md | grep -v '^| scene ' | cut -d'|' -f2,7,8,9,11 | tr '\n' ' ')" >> $T
  timeout 60 $B bench --device gpu -q --spheres 488,8000 --radius 0.1 --accel octree --depth $d --repeat 5 > $R/sph_d$d.md 2>&1
  echo "spheres depth $d rc=$?: $(grep -E '^\| [^-]' $R/sph_d$d.md | grep -v '^| spheres ' | cut -d'|' -f2,6,7,8 | tr '\n' ' ')" >> $T
done
gpu_finish
