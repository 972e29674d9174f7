# Session 26 on the H200, run 1 (expected.md): `--bvh-width 2` against
# `--bvh-width 4` over sphere fields, `--accel bvh`. Carried: .gl, .gpub
# (bin.txz: a52dac3). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "w2=-- --bvh-width 2" --variant "w4=-- --bvh-width 4")
AB_TIMEOUT=120 ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu --accel bvh
for f in 488:0.1 8000:0.1 128000:0.1 1000000:0.1 1000000:0.01; do
  AB_TIMEOUT=150 ab s${f%%:*}_r${f#*:} $S --spheres ${f%%:*} --radius ${f#*:} --accel bvh
done
$B render $S --spheres 8000 --radius 0.1 --accel bvh --bvh-width 2 -q -o $R/w2.pfm
$B render $S --spheres 8000 --radius 0.1 --accel bvh --bvh-width 4 -q -o $R/w4.pfm
cmp -s $R/w2.pfm $R/w4.pfm && echo "8000 w2/w4 identical" >> $T || echo "8000 w2/w4 DIFFERENT" >> $T
rm -f $R/w2.pfm $R/w4.pfm
gpu_finish
