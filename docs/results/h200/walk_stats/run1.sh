# --walk-stats on the H200: the counts against lavapipe's (the same
# tools/walk_stats.py command as docs/results/lavapipe_20261202d), the
# 64-bit carry (brute force over 10,004 spheres: more than 2^32 tests),
# the cost with it off (A/B against c56d0cc, 5 rounds) and on, identity.
# Carried: .gl, .gpub (bin.tgz: app/octrace and the GPU test binaries with
# --walk-stats, octrace-base of c56d0cc, COMMIT), .assets.
set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base; B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; rm -rf $R; mkdir -p $R; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > $T
timeout 120 python3 tools/walk_stats.py --octrace $B --render "--device gpu --size 300x200 --spp 4 --depth 50" --scene "the peer's field, its camera=--scene tools/scenes/peer_field.json" --scene "rtiow 488 spheres, r 0.1=--spheres 488 --radius 0.1" --scene "rtiow 8,000 spheres=--spheres 8000 --radius 0.1" --scene "rtiow 128,000 spheres=--spheres 128000 --radius 0.1" --scene "rtiow 1,000,000 spheres=--spheres 1000000 --radius 0.1" --scene "Viva Balloon (KevinAz61, CC-BY-4.0)=--scene .assets/balloon/scene.gltf" --scene "2CylinderEngine=--scene .assets/2CylinderEngine.glb" --out $R/walk_stats.md > $R/walk_stats.log 2>&1; echo "walk_stats rc=$?" >> $T; cat $R/walk_stats.log >> $T
timeout 60 $B render --device gpu --spheres 10000 --size 1200x800 --spp 1 --depth 1 --accel brute --walk-stats --json -q --out /tmp/carry.pfm > $R/carry.json 2>&1; echo "carry rc=$? $(python3 -c "import json; j=json.load(open('$R/carry.json')); w=j['walk']; print('queries', w['queries'], 'primitives', w['primitives'], 'spheres', j['scene']['spheres'], 'exact' if w['primitives']==w['queries']*j['scene']['spheres'] else 'MISMATCH')")" >> $T
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
V=(--variant base=BIN=$A --variant new= --variant counting=--\ --walk-stats)
ab() { name=$1; shift; timeout 90 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" "${V[@]}" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "$name rc=$?: $(grep -E '^\| (base|new|counting) ' $R/ab_$name.md | cut -d"|" -f2,5,6,7,9 | tr '\n' ' ')" >> $T; }
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab s488 --spheres 488 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for v in $A $B; do
  timeout 30 $v render --scene $sc --size 400x300 --spp 10 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "mesh identity $(basename $sc) 10 spp: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T; done
DEVICE=gpu timeout 100 tools/identity_check.sh $A $B /tmp/id > $R/identity_gpu.txt 2>&1; echo "identity rc=$? $(tail -1 $R/identity_gpu.txt)" >> $T
tar czf $OUT/results.tgz -C /tmp res; cat $T
