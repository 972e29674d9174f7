#!/usr/bin/env bash
# A GPU run script (docs/results/h200/*/run*.sh, which source
# tools/gpu_run.sh) rehearsed on this machine's CPU device before it spends
# the GPU machine's minutes: a typo, a missing binary in the pack, a wrong
# flag or a scene path shows here instead of there.
#
#   tools/gpu_dry_run.sh RUN.sh [OUT_DIR]     (default OUT_DIR: /tmp/gpu_dry)
#
# In a temporary worktree of HEAD (the working tree's changes are not in it;
# the run scripts are copied from the working tree), with the ignored .gpub
# and .assets copied in, the script runs with:
#   - tools/gpu_run.sh without the GPU machine's set-up (no .gl debs, no
#     ldconfig, no NVIDIA ICD, no nvidia-smi, no /work/main link; R and the
#     results under OUT_DIR),
#   - every `--device gpu` turned into `--device cpu`, the images shrunk
#     to 64x48 at 1 spp, 1,000,000 spheres to 100,000, 10,000,000 to
#     200,000 (in the script, and in gpu_run.sh's BENCH and bench_goals:
#     one timed run a configuration),
#   - AB_ROUNDS=1 (one round after the warm-up).
# Then OUT_DIR/summary.txt is printed: each `ab` line with rc=0 and both
# variants, each suite with its result. The figures mean nothing (lavapipe,
# one round); the GPU suites (OCTRACE_TEST_DEVICE=gpu) fail at once here for
# want of a GPU, which the summary shows as their FAILED lines. Takes
# minutes (the binaries run on lavapipe); exit status: the run script's.
set -euo pipefail
run=${1:?usage: tools/gpu_dry_run.sh RUN.sh [OUT_DIR]}
out=${2:-/tmp/gpu_dry}
root=$(cd "$(dirname "$0")/.." && pwd)
[ -f "$run" ] || { echo "gpu_dry_run: $run: no such file" >&2; exit 2; }
[ -f "$root/.gpub/bin.txz" ] || [ -f "$root/.gpub/bin.tgz" ] || {
  echo "gpu_dry_run: $root/.gpub: no bin.txz or bin.tgz (the pack the run unpacks)" >&2
  exit 2
}
run_abs=$(cd "$(dirname "$run")" && pwd)/$(basename "$run")
rel=${run_abs#"$root"/}
[ "$rel" != "$run_abs" ] || { echo "gpu_dry_run: $run is not inside $root" >&2; exit 2; }

tree=$(mktemp -d /tmp/gpu_dry_tree.XXXXXX)
cleanup() { git -C "$root" worktree remove --force "$tree" >/dev/null 2>&1 || rm -rf "$tree"; }
trap cleanup EXIT
git -C "$root" worktree add -q --detach "$tree" HEAD
cp -r "$root/.gpub" "$tree/"
[ -d "$root/.assets" ] && cp -r "$root/.assets" "$tree/"
mkdir -p "$tree/$(dirname "$rel")"
cp "$run_abs" "$tree/$rel"
rm -rf "$out"
mkdir -p "$out/res"
python3 - "$tree/tools/gpu_run.sh" "$tree/$rel" "$out/res" <<'EOF'
import re
import sys
lib, script, res = sys.argv[1:4]
s = open(lib).read()
for old, new in [
    ('for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig', 'true  # dry run: no .gl debs'),
    ('"$B" devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json',
     'true  # dry run: the CPU device'),
    ('mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main', 'true  # dry run: no /work/main link'),
    ('nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader', 'echo "dry run on the CPU device"'),
    ('R=/tmp/res;', 'R=' + res + ';'),
    ('S="--size 1200x800 --spp 10 --depth 50 --device gpu"', 'S="--size 64x48 --spp 1 --depth 50 --device cpu"'),
    ('BENCH="bench --device gpu"', 'BENCH="bench --device cpu --size 64x48 --spp 1 --repeat 1"'),
    ('--spheres 488,8000,1000000 ', '--spheres 488,8000,100000 '),
    ('--spheres 10000000 ', '--spheres 200000 '),
    ('tar czf "$OUT/results.tgz" -C /tmp res;', 'tar czf "$OUT/results.tgz" -C "$(dirname "$R")" "$(basename "$R")";'),
]:
    if old not in s:
        sys.exit("gpu_dry_run: tools/gpu_run.sh changed; cannot find: " + old)
    s = s.replace(old, new)
open(lib, 'w').write(s)

t = open(script).read()
for old, new in [('--device gpu', '--device cpu'), ('1920x1080', '64x48'), ('1200x800', '64x48'),
                 ('600x400', '64x48'), ('10000000', '200000'), ('1000000', '100000')]:
    t = t.replace(old, new)
t = re.sub(r'--spp [0-9]+', '--spp 1', t)
open(script, 'w').write(t)
EOF
rc=0
(cd "$tree" && XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} OUT=$out AB_ROUNDS=1 bash "$rel") > "$out/run.log" 2>&1 || rc=$?
echo "gpu_dry_run: $rel exited $rc; log $out/run.log, summary $out/summary.txt"
cat "$out/summary.txt" 2>/dev/null || true
exit $rc
