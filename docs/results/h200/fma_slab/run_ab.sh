# Optimisation log 35 (FMA slab test) and 33 (restrict), H200 A/B, alternating,
# 5 rounds, device time: four builds of the same commit's host code, the
# shaders differing (base = b4ce7df; fma = the multiply-add slab test; restrict
# = log 33's storage qualifiers; both). Run from the repository root on the
# GPU machine with .gl, .gpub (ab.tgz: the four binaries) and .assets carried.
set -u; mkdir -p /tmp/v; tar xzf .gpub/ab.tgz -C /tmp/v
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=/tmp/v/octrace-base
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat /tmp/v/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V="--variant base= --variant fma=BIN=/tmp/v/octrace-fma --variant restrict=BIN=/tmp/v/octrace-restrict --variant both=BIN=/tmp/v/octrace-both"
ab() { name=$1; shift; timeout 100 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" $V --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name: $(tail -4 $R/ab_$name.md | cut -d'|' -f2,5 | tr '\n' ' ')"; }
{
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab peer_bvh --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu --accel bvh
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab s1m --spheres 1000000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
} | tee $R/summary.txt
DEVICE=gpu timeout 120 tools/identity_check.sh $B /tmp/v/octrace-both /tmp/idw > $R/identity_gpu.txt 2>&1; echo "identity rc=$?" | tee -a $R/summary.txt; tail -2 $R/identity_gpu.txt
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
