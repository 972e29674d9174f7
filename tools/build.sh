#!/usr/bin/env bash
# Installs what octrace needs (tools/setup.sh), configures a Release build in
# build/ and builds it. Safe to run again: every step skips what is done.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build
