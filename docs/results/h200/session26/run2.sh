# Session 26 on the H200, run 2 (expected.md, run 1's table): the 10M
# fields of run 1, `--bvh-width 2` against `--bvh-width 4`, `--accel bvh`.
# Carried: .gl, .gpub (bin.txz: a52dac3). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "w2=-- --bvh-width 2" --variant "w4=-- --bvh-width 4")
for f in 10000000:0.1 10000000:0.01; do
  AB_TIMEOUT=280 ab s${f%%:*}_r${f#*:} $S --spheres ${f%%:*} --radius ${f#*:} --accel bvh
done
gpu_finish
