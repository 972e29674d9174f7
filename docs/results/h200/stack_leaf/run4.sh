# On 476acad (log 40) on the H200: the big list tested before the walk and
# the mesh walk called twice at the top level (527bfd1's form, log 39 undone)
# in two codings, A/B against 476acad (5 rounds, device time), and registers.
# formb: one walk with `const bool BIG_LEAF_FIRST = false` (formb.patch);
# old: the walk and its callers of c740ecf with log 40's stack (old.patch).
# Carried: .gl, .gpub (bin.tgz of run2.sh, form.tgz: octrace-formb, octrace-old), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu; tar xzf .gpub/form.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
for v in formb old; do for sc in tools/scenes/peer_field.json .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do
  echo "regs $v $(basename $sc): $(timeout 30 build-gpu/octrace-$v render --scene $sc --size 320x200 --spp 1 --device gpu --pipeline-stats --out /tmp/ps.png 2>&1 | grep -E '^pipeline  Register' | tr -s ' ')" >> $T
done; done
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base= --variant formb=BIN=build-gpu/octrace-formb --variant old=BIN=build-gpu/octrace-old)
ab() { name=$1; shift; timeout 80 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|formb|old) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab engine --scene .assets/2CylinderEngine.glb $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab s488 --spheres 488 --radius 0.1 $S
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
tar czf $OUT/results.tgz -C /tmp res; cat $T
