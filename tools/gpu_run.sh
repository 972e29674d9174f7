# Sourced by the GPU run scripts (docs/results/h200/*/run*.sh), on the GPU
# machine, in the checkout's copy there, with the carried folders .gl (the
# amd64 debs of the Vulkan loader and GL libraries: docs/reliability.md) and
# .gpub (bin.txz or bin.tgz: build-gpu's binaries and a COMMIT file; xz -9
# keeps several near-identical variant binaries small; tools/gpu_pack.sh
# builds it):
#   - unpacks it into build-gpu and installs .gl's debs;
#   - A=build-gpu/octrace-base, B=build-gpu/app/octrace; points the Vulkan
#     loader at the NVIDIA ICD if B does not find a device without it;
#   - links /work/main to the checkout (the tests' data paths);
#   - R=/tmp/res for raw results, T=$OUT/summary.txt started with the date,
#     build-gpu/COMMIT and the GPU; S = the goals' render settings, BENCH
#     `bench` on the GPU;
#   - ab NAME FLAGS...: tools/ab_render.py of the variants in the array V
#     (set by the script: V=(--variant base=BIN=$A --variant new=)),
#     AB_ROUNDS rounds (5 unless set), AB_METRIC (ab_render.py's
#     --metric: device time unless set, `wall` for the whole process),
#     into $R/ab_NAME.md, one line per variant in $T;
#   - mesh_ab [FLAGS...]: ab over the four meshes the mesh trees are
#     measured on (engine, balloon, sheet: 1M triangles in one mesh,
#     grid400: 400 instances of a 70k grid; the grids made in $R/grid.glb
#     and $R/grid400.glb, kept there for the script), $S and the octree;
#   - same_image LABEL BIN1 BIN2 FLAGS...: renders FLAGS with both
#     binaries and says in $T whether the two PFM files are identical;
#   - pipeline_stats LABEL BIN FLAGS...: BIN's statistics of the
#     pipelines that `render FLAGS` compiles (--pipeline-stats: the
#     path-tracing pipeline's, then the tail's stages'), those whose names
#     say registers, memory or spills, one line in $T;
#   - suite NAME LIMIT: build-gpu/tests/NAME with a time limit of LIMIT
#     seconds, into $R/NAME.txt, its rc and gtest's PASSED/FAILED lines in $T;
#   - gpu_suites: the GPU suites at once (the hard cases in four shards,
#     accel_test, render_test's tail-queue case; 400 s each at most, each
#     with its exit status) while
#     the peer builds (.peers/karim, when carried; peer_build), one line
#     each in $T;
#   - hardcases_shards N LIMIT: the hard cases in N shards at once, each
#     with a limit of LIMIT seconds (a cold shader cache makes the first
#     shards slow: 180 s or more for eight), one line each in $T;
#   - render_cases FILTER LIMIT: render_test's cases that FILTER
#     (--gtest_filter) names, on the GPU, with a limit of LIMIT seconds
#     (the tail-queue case alone took 163 s on a cold cache, session 51),
#     its counts in $T and its output in $OUT/render_test.txt;
#   - peer NAME [RENDER FLAGS]: tools/peer/compare.py side by side into
#     $R/NAME, its two rows in $T;
#   - peer_both: the peer built (unless gpu_suites built it) and side by
#     side with `--accel bvh` and the octree (peer_bvh, peer_octree);
#   - walk_stats LABEL FLAGS...: `render FLAGS --walk-stats`'s counts a
#     query (render --json's walk over its queries), one line in $T;
#   - bench_goals: `bench` of the goals' rows (488 / 8,000 / 1M spheres
#     with both structures, the balloon and the engine, 10M with the BVH)
#     into $OUT/spheres.log, meshes.log and spheres10m.log, their figures
#     in $T;
#   - gpu_finish: $R tarred into $OUT/results.tgz, $T printed.
set -u
rm -rf build-gpu; mkdir build-gpu; tar xf "$(ls .gpub/bin.txz .gpub/bin.tgz 2>/dev/null | head -1)" -C build-gpu
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export XDG_RUNTIME_DIR=/tmp
A=build-gpu/octrace-base; B=build-gpu/app/octrace
"$B" devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /work; [ -e /work/main ] || ln -s "$PWD" /work/main
R=/tmp/res; rm -rf "$R"; mkdir -p "$R"; T=$OUT/summary.txt
{ date -u; cat build-gpu/COMMIT; nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader; } > "$T"
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
BENCH="bench --device gpu"
ab() {
  local name=$1; shift
  local labels; labels=$(printf '%s\n' "${V[@]}" | grep -v '^--variant$' | sed 's/=.*//' | paste -sd'|')
  timeout ${AB_TIMEOUT:-90} python3 tools/ab_render.py --octrace "$B" --rounds ${AB_ROUNDS:-5} ${AB_METRIC:+--metric "$AB_METRIC"} \
    --render "$*" "${V[@]}" --out "$R/ab_$name.md" > "$R/ab_$name.log" 2>&1
  echo "$name rc=$?: $(grep -E "^\| ($labels) " "$R/ab_$name.md" | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> "$T"
}
mesh_ab() {
  [ -f "$R/grid.glb" ] || python3 tools/make_grid_glb.py 708 "$R/grid.glb" > /dev/null
  [ -f "$R/grid400.glb" ] || python3 tools/make_grid_glb.py 187 "$R/grid400.glb" 400 > /dev/null
  AB_TIMEOUT=${AB_TIMEOUT:-240} ab engine $S --scene .assets/2CylinderEngine.glb --accel octree "$@"
  AB_TIMEOUT=${AB_TIMEOUT:-240} ab balloon $S --scene .assets/balloon/scene.gltf --accel octree "$@"
  AB_TIMEOUT=${AB_TIMEOUT:-240} ab sheet $S --scene "$R/grid.glb" --accel octree "$@"
  AB_TIMEOUT=${AB_TIMEOUT:-240} ab grid400 $S --scene "$R/grid400.glb" --accel octree "$@"
}
same_image() {
  local label=$1 one=$2 two=$3; shift 3
  "$one" render "$@" -q -o "$R/same_1.pfm"; "$two" render "$@" -q -o "$R/same_2.pfm"
  cmp -s "$R/same_1.pfm" "$R/same_2.pfm" && echo "$label identical: $*" >> "$T" || echo "$label DIFFERENT: $*" >> "$T"
  rm -f "$R/same_1.pfm" "$R/same_2.pfm"
}
pipeline_stats() {
  local label=$1 bin=$2; shift 2
  echo "$label: $("$bin" render "$@" --pipeline-stats --json -q -o "$R/stats.pfm" 2>/dev/null |
    python3 -c 'import json,re,sys; s=json.load(sys.stdin).get("pipeline_statistics") or {}; print(json.dumps({k: v for k, v in s.items() if re.search("regist|memory|spill", k, re.I)}))' | head -c 1200)" >> "$T"
  rm -f "$R/stats.pfm"
}
# gtest's PASSED/FAILED lines of a test's output FILE, on one line.
# With gpu_suites' exit status line (124: its time limit cut it off).
gtest_result() { grep -E '^\[  (PASSED|FAILED|rc=)' "$1" | tr '\n' ' '; }
suite() {
  timeout "$2" "build-gpu/tests/$1" > "$R/$1.txt" 2>&1
  echo "$1 rc=$? $(gtest_result "$R/$1.txt")" >> "$T"
}
# gpu_suites' runner: COMMAND... with a 400 s limit (suite_logged_for:
# LIMIT seconds) into FILE, its exit status (124: the limit cut it off) as
# FILE's last line.
suite_logged() { suite_logged_for 400 "$@"; }
suite_logged_for() {
  local limit=$1 file=$2; shift 2
  timeout "$limit" "$@" > "$file" 2>&1
  echo "[  rc=$? ]" >> "$file"
}
# The peer's build (.peers/karim) into $R/peer_build.log, its exit status in $T.
peer_build() { (cd .peers/karim && ./build.sh > "$R/peer_build.log" 2>&1); echo "peer build rc=$?" >> "$T"; }
# The GPU tests' environment: their device and the folder they write to.
gpu_tests() { export OCTRACE_TEST_DEVICE=gpu; mkdir -p build-gpu/tests/tmp; }
gpu_suites() {
  gpu_tests
  hardcases_shards 4 400 &
  suite_logged "$R/accel_test.txt" build-gpu/tests/accel_test &
  suite_logged "$R/render_test.txt" build-gpu/tests/render_test --gtest_filter='*TailQueue*' &
  [ -d .peers/karim ] && peer_build &
  wait
  echo "accel_test: $(gtest_result "$R/accel_test.txt")" >> "$T"
  echo "render_test tail: $(gtest_result "$R/render_test.txt")" >> "$T"
  echo "suites done at $(date -u +%T)" >> "$T"
}
hardcases_shards() {
  local n=$1 limit=$2 k f
  gpu_tests
  for ((k = 0; k < n; ++k)); do
    GTEST_TOTAL_SHARDS=$n GTEST_SHARD_INDEX=$k suite_logged_for "$limit" "$R/hardcases_$k.txt" build-gpu/tests/hardcases_test &
  done
  wait
  for ((k = 0; k < n; ++k)); do
    echo "hardcases shard $k of $n: $(gtest_counts "$R/hardcases_$k.txt")" >> "$T"
  done
}
# gtest's cases that passed and failed in FILE (a case cut off by a time
# limit is neither), then its PASSED/FAILED lines.
gtest_counts() {
  echo "ok $(grep -c '^\[       OK \]' "$1"), failed $(grep -cE '^\[  FAILED  \] .* \([0-9]+ ms\)$' "$1") $(gtest_result "$1")"
}
render_cases() {
  gpu_tests
  timeout "$2" build-gpu/tests/render_test --gtest_filter="$1" > "$R/render_test.txt" 2>&1
  echo "render_test $1: $(gtest_counts "$R/render_test.txt")" >> "$T"
  cp "$R/render_test.txt" "$OUT/"
}
peer() {
  local name=$1; shift
  timeout 70 python3 tools/peer/compare.py --peer .peers/karim --octrace "$B" --out "$R/$name" ${1:+--octrace-args "$*"} > "$R/$name.log" 2>&1
  echo "$name rc=$?: $(grep -E '\| (CUDA|octrace)' "$R/$name/peer_compare.md" | tr '\n' ' ')" >> "$T"
}
peer_both() {
  [ -f "$R/peer_build.log" ] || peer_build
  peer peer_bvh --accel bvh
  peer peer_octree --accel octree
}
# One `bench` of the goals' rows: NAME, a time limit in seconds, the lines
# of its log that go into $T (a grep pattern), then bench's flags.
bench_logged() {
  local name=$1 limit=$2 pattern=$3; shift 3
  timeout "$limit" "$B" $BENCH "$@" > "$OUT/$name.log" 2>&1
  echo "bench $name rc=$?" >> "$T"; grep -E "$pattern" "$OUT/$name.log" | grep -v '^[#|]' >> "$T"
}
bench_goals() {
  bench_logged spheres 150 " ms" --accel octree,bvh --spheres 488,8000,1000000 --radius 0.1
  bench_logged meshes 90 "rays/s$" --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
  bench_logged spheres10m 150 " ms" --accel bvh --spheres 10000000 --radius 0.1
}
walk_stats() {
  local label=$1; shift
  "$B" render "$@" --walk-stats --json -q -o "$R/walk.pfm" > "$R/walk_$label.json" 2>&1
  echo "walk-stats $label: $(python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["walk"]; q=w["queries"]; print({k: round(v / q, 3) for k, v in w.items()})' "$R/walk_$label.json" 2>&1 | head -c 600)" >> "$T"
  rm -f "$R/walk.pfm"
}
gpu_finish() { tar czf "$OUT/results.tgz" -C /tmp res; cat "$T"; }
