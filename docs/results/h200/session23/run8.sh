# Session 23 on the H200, run 8 (expected.md): render --spp 1 and 11 at 1M
# and 10M spheres. Carried: .gl, .gpub (run 5's bin.txz), .assets.
source tools/gpu_run.sh
for n in 1000000 10000000; do for spp in 1 11; do
  $B render --size 1200x800 --depth 50 --device gpu --spp $spp --spheres $n --radius 0.1 --accel bvh --json -q -o $R/r.png > $R/render_${n}_$spp.json 2> $R/render_${n}_$spp.err
  echo "render $n spheres spp $spp: $(python3 -c "import json; j=json.load(open('$R/render_${n}_$spp.json')); t=j['times_ms']; print(round(t['render'],1), 'ms; upload', round(t['upload']), 'accel_build', round(t['accel_build']))")" >> $T
done; done
rm -f $R/r.png
gpu_finish
