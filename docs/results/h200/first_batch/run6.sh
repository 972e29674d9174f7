# The final code of log 42 (next_batch, adf6a26 and after) on the H200
# against ae06230, which run4 measured: `render` A/B, 5 rounds, and the
# identity check. Expected: the same times (fast passes take the same
# batches) and 36/36 bit-identical. Carried: .gl, .gpub, .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-ae06230; B=build-gpu/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; echo "octrace: $(cat build-gpu/COMMIT); octrace-ae06230"; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant ae06230= --variant final=BIN=$B)
ab() { name=$1; shift; timeout 40 python3 tools/ab_render.py --octrace $A --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (ae06230|final) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab balloon --scene .assets/balloon/scene.gltf $S
ab s488 --spheres 488 --radius 0.1 $S
DEVICE=gpu timeout 60 tools/identity_check.sh $A $B /tmp/id > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
