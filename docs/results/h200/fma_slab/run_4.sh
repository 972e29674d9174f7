# Optimisation log 37: the scalar-margin multiply-add slab test in the mesh
# walk only (meshfma: the top-level walk keeps subtract-multiply), and with
# the per-axis form in the top-level walk (axis_meshfma), against base
# (bc55933). H200, A/B alternating, 5 rounds, device time; registers; the
# image identity check. Carried: .gl, .gpub (ab5.tgz), .assets.
set -u; mkdir -p /tmp/v; tar xzf .gpub/ab5.tgz -C /tmp/v
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=/tmp/v/octrace-base
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat /tmp/v/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V="--variant base= --variant meshfma=BIN=/tmp/v/octrace-meshfma --variant axis_meshfma=BIN=/tmp/v/octrace-axis_meshfma"
ab() { name=$1; shift; timeout 70 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" $V --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name: $(tail -3 $R/ab_$name.md | cut -d'|' -f2,5,9 | tr '\n' ' ')"; }
{
ab engine --scene .assets/2CylinderEngine.glb $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab s1m --spheres 1000000 --radius 0.1 $S
} | tee $R/summary.txt
for v in base meshfma axis_meshfma; do for sc in "peer|--scene tools/scenes/peer_field.json" "balloon|--scene .assets/balloon/scene.gltf" "engine|--scene .assets/2CylinderEngine.glb"; do
  echo "== $v ${sc%%|*} $(timeout 60 /tmp/v/octrace-$v render ${sc#*|} --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/o.png 2>&1 | grep 'Register Count')"
done; done | tee -a $R/summary.txt
DEVICE=gpu timeout 90 tools/identity_check.sh $B /tmp/v/octrace-axis_meshfma /tmp/idw > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" | tee -a $R/summary.txt
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
