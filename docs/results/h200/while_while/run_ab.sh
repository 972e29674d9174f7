# Optimisation log 38: the while-while walk (ww) and its speculative form
# (wws: a leaf postponed until every active invocation of the subgroup holds
# one, subgroupAll) against base (5cfde10), H200 A/B alternating, 5 rounds,
# device time; registers; the peer and octrace at depth 1 and 2 (where the
# time goes); the image identity check base against both.
# Carried: .gl, .gpub (ww.tgz: three binaries, the ww and wws test binaries), .assets, .peers.
set -u; mkdir -p /tmp/v; tar xzf .gpub/ww.tgz -C /tmp/v
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=/tmp/v/octrace-base
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=$OUT/res; mkdir -p $R; date -u > $R/date.txt; cat /tmp/v/COMMIT >> $R/date.txt
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader >> $R/date.txt
(cd .peers/karim && ./build.sh > $R/peer_build.txt 2>&1) &
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --rr-depth 1 --device gpu"
V="--variant base= --variant ww=BIN=/tmp/v/octrace-ww --variant wws=BIN=/tmp/v/octrace-wws"
ab() { name=$1; shift; timeout 75 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" $V --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name: $(tail -3 $R/ab_$name.md | cut -d'|' -f2,5,9 | tr '\n' ' ')"; }
{
ab peer $P --depth 50
ab peer_bvh $P --depth 50 --accel bvh
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab s1m --spheres 1000000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
} | tee $R/summary.txt
wait
for d in 1 2 50; do
  for a in octree bvh; do echo "octrace depth $d $a: $(timeout 30 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$P --depth $d --accel $a" --variant base= 2>&1 | tail -1)"; done
  echo "peer depth $d: $(cd .peers/karim && timeout 30 ./karim_bench 1920 1080 64 $d 0 2>/dev/null | tail -1)"
done | tee -a $R/summary.txt
for v in base ww wws; do for sc in "--scene tools/scenes/peer_field.json" "--scene .assets/2CylinderEngine.glb"; do
  echo "$v $sc: $(timeout 30 /tmp/v/octrace-$v render $sc --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png 2>&1 | grep -E '^pipeline  (Register|Stack|Local)' | tr -s ' ' | tr '\n' ' ')"
done; done | tee $R/pipeline_stats.txt
for v in ww wws; do DEVICE=gpu timeout 90 tools/identity_check.sh $B /tmp/v/octrace-$v /tmp/id_$v > $R/identity_gpu_$v.txt 2>&1; echo "identity $v rc=$? $(tail -1 $R/identity_gpu_$v.txt)"; done | tee -a $R/summary.txt
ls -la $R
