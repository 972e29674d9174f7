# Session 20 on the H200, run 2 (expected.md): `bench` of the sphere fields
# after log 62, both structures; throwaway VT (triangles as whole vectors)
# against e993f32 on the balloon and the engine, both structures, images
# compared.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "kept=" --variant "VT=BIN=build-gpu/var/VT")
for a in octree bvh; do
  ab balloon_$a $S --scene .assets/balloon/scene.gltf --accel $a
  ab engine_$a $S --scene .assets/2CylinderEngine.glb --accel $a
  for m in .assets/balloon/scene.gltf .assets/2CylinderEngine.glb; do
    $B render --scene $m --size 320x180 --spp 4 --depth 50 --device gpu --accel $a -q -o $R/k.pfm
    build-gpu/var/VT render --scene $m --size 320x180 --spp 4 --depth 50 --device gpu --accel $a -q -o $R/v.pfm
    cmp $R/k.pfm $R/v.pfm && echo "VT identical $a $m" >> $T || echo "VT DIFFERENT $a $m" >> $T
  done
done
rm -f $R/*.pfm
timeout 200 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1
echo "bench spheres rc=$?" >> $T; grep -E '^\| [0-9]' $R/spheres.log >> $T
timeout 150 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 --csv $R/s10m.csv > $R/s10m.log 2>&1
echo "10M bvh rc=$?" >> $T; grep -E '^\| [0-9]' $R/s10m.log >> $T
gpu_finish
