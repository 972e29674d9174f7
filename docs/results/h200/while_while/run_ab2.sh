# Optimisation log 38, second run: the while-while walk in every walk (ww),
# in the octree walks only (wwoct: both levels, the BVH walks as before) and
# in the mesh walks only (wwmesh: octree and BVH), against base (5cfde10);
# H200 A/B alternating, 5 rounds, device time. Then octrace's camera rays
# alone (--depth 1) on the peer's scene, for the peer's depth-1 figure of run 1.
# Carried: .gl, .gpub (ww2.tgz), .assets.
set -u; mkdir -p /tmp/v; tar xzf .gpub/ww2.tgz -C /tmp/v
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=/tmp/v/octrace-base
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat /tmp/v/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --rr-depth 1 --device gpu"
V4="--variant base= --variant ww=BIN=/tmp/v/octrace-ww --variant wwoct=BIN=/tmp/v/octrace-wwoct --variant wwmesh=BIN=/tmp/v/octrace-wwmesh"
V2="--variant base= --variant ww=BIN=/tmp/v/octrace-ww"
ab() { name=$1; vs=$2; shift 2; timeout 70 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" $vs --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name: $(tail -4 $R/ab_$name.md | cut -d'|' -f2,5,9 | tr '\n' ' ')"; }
{
ab s488 "$V4" --spheres 488 --radius 0.1 $S
ab s8000 "$V4" --spheres 8000 --radius 0.1 $S
ab s1m "$V2" --spheres 1000000 --radius 0.1 $S
ab peer "$V4" $P --depth 50
ab peer_bvh "$V4" $P --depth 50 --accel bvh
ab balloon "$V4" --scene .assets/balloon/scene.gltf $S
ab engine "$V4" --scene .assets/2CylinderEngine.glb $S
ab balloon_bvh "$V4" --scene .assets/balloon/scene.gltf $S --accel bvh
ab engine_bvh "$V4" --scene .assets/2CylinderEngine.glb $S --accel bvh
} | tee $R/summary.txt
timeout 40 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$P --depth 1" --variant octree= --variant "bvh=-- --accel bvh" --out $R/ab_peer_depth1.md > $R/ab_peer_depth1.log 2>&1
echo "peer_depth1: $(tail -2 $R/ab_peer_depth1.md | cut -d'|' -f2,5,9 | tr '\n' ' ')" | tee -a $R/summary.txt
cp $R/summary.txt $OUT/; tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
