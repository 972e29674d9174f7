#!/usr/bin/env bash
# Runs the libFuzzer targets of tests/fuzz/ for a given time each and reports,
# per target, the executions, the coverage (libFuzzer's cov: edges and ft:
# features), the corpus size at the end and the findings.
#
#   tools/fuzz.sh [SECONDS] [TARGET...]     (default: 60 s; scene_json gltf image)
#
# Builds build-fuzz/ with clang (-DOCTRACE_FUZZ=ON: libFuzzer, ASan, UBSan),
# then runs each target on a copy of its corpus (tests/fuzz/corpus/TARGET/) in
# build-fuzz/run/TARGET/ with -timeout=1 (an input that takes longer than 1 s
# is a finding), -rss_limit_mb=2048 and leak detection. A finding is kept as
# build-fuzz/run/TARGET/findings/{crash,timeout,leak,oom}-*; the run stops at
# the first one. Put it into the corpus (and a unit test) once it is fixed:
# docs/reliability.md says how. Exit status 1 if any target found something.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_json gltf image)

tools/setup.sh
if [ ! -f build-fuzz/build.ninja ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOCTRACE_FUZZ=ON
fi
cmake --build build-fuzz --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="detect_leaks=1"
# Leaks inside libraries that octrace does not build; tools/lsan.supp says which and why.
export LSAN_OPTIONS="suppressions=$root/tools/lsan.supp"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
printf '%-11s %12s %8s %8s %8s %7s  %s\n' target executions exec/s cov ft corpus findings
for t in "${targets[@]}"; do
  run=build-fuzz/run/$t
  rm -rf "$run"
  mkdir -p "$run/corpus" "$run/findings"
  cp "$root/tests/fuzz/corpus/$t/"* "$run/corpus/"
  # Run in an empty folder: a scene's mesh file or a glTF's external buffer
  # named by a fuzzed input is looked for there, and is not found.
  (cd "$run" && "$root/build-fuzz/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=1 \
     -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=findings/ corpus >log.txt 2>&1) || true
  log=$run/log.txt
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corpus=$(ls "$run/corpus" | wc -l)
  findings=$(ls "$run/findings")
  printf '%-11s %12s %8s %8s %8s %7s  %s\n' "$t" "${execs:-?}" "${speed:-?}" "${cov:-?}" "${ft:-?}" "$corpus" \
    "${findings:-none}"
  if [ -n "$findings" ] || [ -z "$execs" ]; then
    status=1
    echo "  $t: see $log" >&2
  fi
done
exit $status
