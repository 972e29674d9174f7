# Log 46 on the H200: `render` A/B against c56d0cc (5 rounds, device time)
# with workgroups of 32 invocations: the sphere fields, the peer's scene, the
# meshes; identity (tools/identity_check.sh, the meshes, lanes 1-8).
# Carried: .gl, .gpub (bin.tgz: app/octrace and the GPU test binaries with
# PATH_GROUP 32, octrace-base of c56d0cc, COMMIT), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base; B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base=BIN=$A --variant group32=)
ab() { name=$1; shift; timeout 60 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|group32) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab peer_bvh --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu --accel bvh
ab s488 --spheres 488 --radius 0.1 $S
ab s488_l1 --spheres 488 --radius 0.1 $S --sample-lanes 1
ab s8000 --spheres 8000 --radius 0.1 $S
ab s1M --spheres 1000000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
for acc in octree bvh; do for v in $A $B; do timeout 30 $v render --scene tools/scenes/peer_field.json --size 400x300 --spp 10 --accel $acc --device gpu -q --out /tmp/p_$(basename $v).pfm; done
  echo "peer scene identity $acc 10 spp: $(cmp /tmp/p_octrace-base.pfm /tmp/p_octrace.pfm && echo bit-identical)" >> $T; done
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for v in $A $B; do
  timeout 30 $v render --scene $sc --size 401x299 --spp 10 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "mesh identity $(basename $sc) 10 spp: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T; done
for l in 1 2 4 8; do for v in $A $B; do timeout 30 $v render --spheres 488 --size 401x299 --spp 16 --sample-lanes $l --device gpu -q --out /tmp/s_$(basename $v).pfm; done
  echo "sphere identity 488 lanes $l: $(cmp /tmp/s_octrace-base.pfm /tmp/s_octrace.pfm && echo bit-identical)" >> $T; done
DEVICE=gpu timeout 100 tools/identity_check.sh $A $B /tmp/id > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
