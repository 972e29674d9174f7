# Run 6 (14:05 UTC): session 30's run1.sh without its last part (the shared-stack A/B, run 9): the host's read-back and writes, caad71e against HEAD. Carried: .gl, .gpub, .assets.
# Prepared in session 30 (no GPU lent there), for the next session with one:
# the host's read-back and image writes on the H200 machine (logs 95, 97-100)
# against caad71e's, and session 29's run 5 (HEAD against the shared-stack
# build at N = 0). Expectations: expected.md ("Prepared for the next GPU
# session"). Carried: .gl, .gpub (bin.txz: COMMIT says which binary is
# which), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
C=build-gpu/octrace-caad
hostab() {  # NAME METRIC RENDER-FLAGS...: caad71e against HEAD
  local name=$1 metric=$2; shift 2
  timeout 120 python3 tools/ab_render.py --octrace "$B" --rounds 5 --metric "$metric" --render "$*" \
    --variant "caad71e=BIN=$C" --variant "head=" --out "$R/ab_$name.md" > "$R/ab_$name.log" 2>&1
  echo "$name rc=$?: $(grep -E '^\| (caad71e|head) ' "$R/ab_$name.md" | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> "$T"
}
hostab readback_1200x800 readback $S -o $R/w.png
hostab write_png_1200x800 write $S -o $R/w.png
hostab wall_1200x800 wall $S -o $R/w.png
P1="--size 1920x1080 --spp 4 --depth 50 --device gpu"
hostab readback_1920x1080 readback $P1 -o $R/w.png
hostab write_png_1920x1080 write $P1 -o $R/w.png
hostab write_exr_1920x1080 write $P1 -o $R/w.exr
hostab write_pfm_1920x1080 write $P1 -o $R/w.pfm
$C render $P1 -q -o $R/a.exr; $B render $P1 -q -o $R/b.exr
cmp -s $R/a.exr $R/b.exr && echo "exr caad71e/HEAD identical" >> $T || echo "exr caad71e/HEAD DIFFERENT" >> $T
$C render $P1 -q -o $R/a.png; $B render $P1 -q -o $R/b.png
echo "png caad71e/HEAD: $($B compare --json $R/a.png $R/b.png | tr -d ' \n')" >> $T
rm -f $R/w.* $R/a.* $R/b.*
gpu_finish
