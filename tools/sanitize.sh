#!/usr/bin/env bash
# Builds everything with AddressSanitizer and UndefinedBehaviorSanitizer into
# build-asan/ (CMake option OCTRACE_SANITIZE) and runs the whole test suite
# under them. Any report fails the test that made it. Leaks inside the Vulkan
# loader, lavapipe and LLVM are suppressed by tools/lsan.supp (each line says
# why); none of octrace's are. Extra arguments go to ctest (e.g. -L unit).
# Last full run: docs/reliability.md.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
if [ ! -f build-asan/build.ninja ]; then
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOCTRACE_SANITIZE=ON
fi
cmake --build build-asan
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# No list of the suppressions used at exit: it would be part of every
# octrace process's output, which the CLI tests read (one line of error, the
# --json summary).
export LSAN_OPTIONS="suppressions=$PWD/tools/lsan.supp:print_suppressions=0"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
# fuzz_run builds and runs the fuzz targets, which have their own sanitizers.
ctest --test-dir build-asan --output-on-failure -j2 -LE fuzz_run "$@"
