#!/usr/bin/env bash
# Builds the pack a GPU run script unpacks (.gpub/bin.txz: tools/gpu_run.sh):
# a commit's app/octrace and GPU test binaries, and one octrace binary per
# probe patch applied on that commit, with a COMMIT file that says which is
# which. The GPU machine builds nothing: every binary travels in the pack.
#
#   tools/gpu_pack.sh [--base REV] [--out FILE] [NAME=PATCH ...]
#
#   --base REV   the commit to build (default HEAD; the working tree's own
#                changes are not in it)
#   --out FILE   where the pack goes (default .gpub/bin.txz; an existing
#                one is kept as FILE.old)
#   NAME=PATCH   build-gpu/octrace-NAME in the pack: REV with PATCH applied
#                (`git apply`; a path relative to the repository root)
#
# Builds in a temporary worktree of REV (build-pack/ in it: Release,
# OCTRACE_WINDOW=OFF, OCTRACE_MPI=OFF, OCTRACE_TESTS=ON, as build-gpu),
# then packs app/octrace, tests/{hardcases_test,accel_test,render_test} and
# the probes with xz -9 (near-identical binaries pack small). Takes a full
# build (minutes on 2 cores) and one relink per probe. Exit status 2 for a
# bad argument or a patch that does not apply.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
base=HEAD
out=$root/.gpub/bin.txz
probes=()
while [ $# -gt 0 ]; do
  case $1 in
    --base) base=${2:?gpu_pack: --base needs a commit}; shift 2 ;;
    --out) out=${2:?gpu_pack: --out needs a file}; shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *=*) probes+=("$1"); shift ;;
    *) echo "gpu_pack: $1: not NAME=PATCH, --base or --out" >&2; exit 2 ;;
  esac
done
rev=$(git -C "$root" rev-parse --verify --quiet "$base^{commit}") || { echo "gpu_pack: $base: no such commit" >&2; exit 2; }
short=$(git -C "$root" rev-parse --short "$rev")
for p in "${probes[@]}"; do
  name=${p%%=*} patch=${p#*=}
  [[ $name =~ ^[A-Za-z0-9_-]+$ ]] || { echo "gpu_pack: $name: a probe's name is letters, digits, - and _" >&2; exit 2; }
  [ -f "$root/$patch" ] || { echo "gpu_pack: $patch: no such file" >&2; exit 2; }
done

work=$(mktemp -d /tmp/gpu_pack.XXXXXX)
stage=$work/stage
tree=$work/tree
cleanup() { git -C "$root" worktree remove --force "$tree" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
git -C "$root" worktree add --quiet --detach "$tree" "$rev"
mkdir -p "$stage/app" "$stage/tests"
# The tests read the repository's files from /work/main, which
# tools/gpu_run.sh links to the checkout on the GPU machine (the worktree
# here is gone by then).
cmake -S "$tree" -B "$tree/build-pack" -G Ninja -DCMAKE_BUILD_TYPE=Release -DOCTRACE_WINDOW=OFF -DOCTRACE_MPI=OFF \
  -DOCTRACE_TESTS=ON -DOCTRACE_TEST_SOURCE_DIR=/work/main > "$work/configure.log"
tests=(hardcases_test accel_test render_test)
ninja -C "$tree/build-pack" app/octrace "${tests[@]/#/tests/}" > "$work/build.log" || { tail -20 "$work/build.log" >&2; exit 1; }
cp "$tree/build-pack/app/octrace" "$stage/app/"
for t in "${tests[@]}"; do cp "$tree/build-pack/tests/$t" "$stage/tests/"; done
echo "app/octrace, tests/{$(IFS=,; echo "${tests[*]}")}: $short, built $(date -u +%FT%TZ) by tools/gpu_pack.sh" \
  "(Release, OCTRACE_WINDOW=OFF OCTRACE_MPI=OFF)" > "$stage/COMMIT"
for p in "${probes[@]}"; do
  name=${p%%=*} patch=${p#*=}
  git -C "$tree" apply "$root/$patch" || { echo "gpu_pack: $patch does not apply to $short" >&2; exit 2; }
  ninja -C "$tree/build-pack" app/octrace >> "$work/build.log" || { tail -20 "$work/build.log" >&2; exit 1; }
  cp "$tree/build-pack/app/octrace" "$stage/octrace-$name"
  echo "octrace-$name: $short + $patch" >> "$stage/COMMIT"
  git -C "$tree" checkout --quiet -- .
done
mkdir -p "$(dirname "$out")"
(cd "$stage" && tar cf - . | xz -9 -T0 > "$work/pack.txz")  # no partial pack at $out if this fails
[ -f "$out" ] && mv "$out" "$out.old"
mv "$work/pack.txz" "$out"
cat "$stage/COMMIT"
echo "gpu_pack: $out ($(du -h "$out" | cut -f1))"
