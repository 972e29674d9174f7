# Three builds on the H200: base (075c55a), lanes (+ first_batch_lanes.patch),
# split (+ whole rounds per dispatch, the rest in a dispatch of fewer lanes).
# `render` A/B alternating, 5 rounds, device time; then `bench` (one batch
# of all samples), the three binaries alternating, 3 times each.
# Carried: .gl, .gpub (bin.tgz), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base
$A devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base= --variant lanes=BIN=build-gpu/octrace-lanes --variant split=BIN=build-gpu/octrace-split)
ab() { name=$1; shift; timeout 90 python3 tools/ab_render.py --octrace $A --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|lanes|split) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
for i in 1 2 3; do for v in base lanes split; do
  timeout 60 build-gpu/octrace-$v bench --device gpu -q --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --accel octree --repeat 5 --csv $R/bench_mesh_${v}_$i.csv > $R/bench_mesh_${v}_$i.md 2>&1
  timeout 60 build-gpu/octrace-$v bench --device gpu -q --spheres 488,8000 --accel octree --repeat 5 --csv $R/bench_sph_${v}_$i.csv > $R/bench_sph_${v}_$i.md 2>&1
done; done
head -3 $R/bench_mesh_base_1.csv >> $T
for k in mesh sph; do for v in base lanes split; do echo "bench $k $v: $(for i in 1 2 3; do tail -n +2 $R/bench_${k}_${v}_$i.csv | cut -d, -f8-15 | tr '\n' ' '; echo -n ' || '; done)" >> $T; done; done
tar czf $OUT/results.tgz -C /tmp res; cat $T
