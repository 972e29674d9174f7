set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace; O=build-gpu/app/octrace-old
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
ab() { name=$1; shift; timeout 60 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" --variant "base=BIN=$O" --variant "restrict=" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name: $(tail -2 $R/ab_$name.md | cut -d'|' -f2,5 | tr '\n' ' ')"; }
{
timeout 90 python3 tools/ab_render.py --octrace $B --rounds 5 --render "--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu" --variant "base=BIN=$O" --variant "restrict=" --variant "bvh_base=BIN=$O -- --accel bvh" --variant "bvh_restrict=-- --accel bvh" --out $R/ab_peer.md > $R/ab_peer.log 2>&1; echo "peer: $(tail -4 $R/ab_peer.md | cut -d'|' -f2,5 | tr '\n' ' ')"
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab s1m --spheres 1000000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
} | tee $R/summary.txt
timeout 120 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer --rounds 5 > $R/peer.log 2>&1; echo "peer rc=$?"; tail -3 $R/peer/peer_compare.md
rm -f $R/peer/*.ppm $R/peer/*.pfm $R/peer/*.png; tar czf $OUT/bench.tgz -C /tmp res
export OCTRACE_TEST_DEVICE=gpu
for t in accel_test effects_test; do
  timeout 80 build-gpu/tests/$t > $R/gpu_$t.txt 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_$t.txt | tr '\n' ' ')"; grep "^\[  FAILED" $R/gpu_$t.txt | head -5
done
OCTRACE_HARDCASES_TABLE=$R/hardcases_gpu.tsv timeout 220 build-gpu/tests/hardcases_test > $R/gpu_hardcases_test.txt 2>&1; echo "hardcases rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/gpu_hardcases_test.txt | tr '\n' ' ')"; grep "^\[  FAILED" $R/gpu_hardcases_test.txt | head -5
tar czf $OUT/tests.tgz -C /tmp res
timeout 50 $B bench --device gpu --accel octree,bvh --spheres 488,8000,128000,1000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.md 2>$R/bench.log; tail -8 $R/spheres.md
timeout 30 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/meshes.csv > $R/meshes.md 2>> $R/bench.log; tail -4 $R/meshes.md
tar czf $OUT/all.tgz -C /tmp res; ls -la $OUT
