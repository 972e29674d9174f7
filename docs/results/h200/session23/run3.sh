# Session 23 on the H200, run 3 (expected.md): base, vt and vt2 in one
# alternation, 9 rounds, both meshes and structures; 10M spheres `render`
# at 10 and 20 spp. Carried: .gl, .gpub (bin.txz: app/octrace = vt2,
# octrace-base, var/vt), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
abn() {  # ab with ROUNDS rounds
  local name=$1 rounds=$2; shift 2
  timeout ${AB_TIMEOUT:-90} python3 tools/ab_render.py --octrace "$B" --rounds $rounds --render "$*" "${V[@]}" --out "$R/ab_$name.md" > "$R/ab_$name.log" 2>&1
  echo "$name rc=$?: $(grep -E '^\| [a-z0-9]+ ' "$R/ab_$name.md" | grep -v variant | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> "$T"
}
V=(--variant "base=BIN=$A" --variant "vt=BIN=build-gpu/var/vt" --variant "vt2=")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do for a in bvh octree; do
  AB_TIMEOUT=100 abn ${sc%%:*}_$a 9 $S --scene ${sc#*:} --accel $a
done; done
for spp in 10 20; do
  $B render --size 1200x800 --spp $spp --depth 50 --device gpu --spheres 10000000 --radius 0.1 --accel bvh --json -q -o $R/r10m.png > $R/render10m_$spp.json 2> $R/render10m_$spp.err
  echo "render 10M spp $spp: $(python3 -c "import json; j=json.load(open('$R/render10m_$spp.json')); print(round(j['times_ms']['render'],1), 'ms')")" >> $T
done
rm -f $R/r10m.png
gpu_finish
