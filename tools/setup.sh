#!/usr/bin/env bash
# Installs every Debian package octrace needs to build, test and render
# (clang and libclang-rt-14-dev, which holds libFuzzer: tools/fuzz.sh; OpenMPI
# for `mpirun -np N octrace render`, CMake option OCTRACE_MPI; python3-zstandard
# for tools/nvidia_sass.py).
# Idempotent and non-interactive: packages already present are skipped, and
# apt-get runs only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools
  libglm-dev libglfw3-dev libstb-dev zlib1g-dev nlohmann-json3-dev libcli11-dev
  libtinyexr-dev libtinygltf-dev libgtest-dev
  assimp-testmodels
  clang libclang-rt-14-dev
  xvfb xauth python3 python3-matplotlib python3-numpy python3-zstandard
  libegl1 libegl-mesa0
  openmpi-bin libopenmpi-dev
  time
)

# Optional (CI does not need it): OCTRACE_SETUP_MITSUBA=1 also creates
# .venv-mitsuba with Mitsuba 3 from PyPI for tools/peer/mitsuba_compare.py
# (which otherwise creates it on first use). Debian's python3 needs
# python3-venv for that.
if [ "${OCTRACE_SETUP_MITSUBA:-0}" = 1 ]; then
  packages+=(python3-venv)
fi
# Optional too: OCTRACE_SETUP_PROFILING=1 adds perf, gdb and objdump for
# tools/llvmpipe_profile.py (where llvmpipe's time goes, per instruction).
if [ "${OCTRACE_SETUP_PROFILING:-0}" = 1 ]; then
  packages+=(linux-perf gdb binutils)
fi

# Optional too: OCTRACE_SETUP_LAVAPIPE=backports also unpacks Debian 12's
# bookworm-backports lavapipe (Mesa 25) into .lavapipe-backports/ beside the
# system's driver, for VK_ICD_FILENAMES (tools/lavapipe_backports.sh says
# why; optimisation log 88). The system's driver stays as it is.
case "${OCTRACE_SETUP_LAVAPIPE:-}" in
  "" | backports) ;;
  *)
    echo "setup: OCTRACE_SETUP_LAVAPIPE=${OCTRACE_SETUP_LAVAPIPE}: expected 'backports' or nothing" >&2
    exit 2
    ;;
esac
setup_lavapipe() {
  if [ "${OCTRACE_SETUP_LAVAPIPE:-}" = backports ]; then "$(dirname "$0")/lavapipe_backports.sh"; fi
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

setup_mitsuba() {
  if [ "${OCTRACE_SETUP_MITSUBA:-0}" = 1 ]; then
    local root venv
    root=$(cd "$(dirname "$0")/.." && pwd)
    venv="$root/.venv-mitsuba"
    [ -x "$venv/bin/python" ] || python3 -m venv "$venv"
    "$venv/bin/python" -m pip install -q "mitsuba==3.9.1" numpy
    echo "setup: Mitsuba 3 in $venv"
  fi
}

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  setup_mitsuba
  setup_lavapipe
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
setup_mitsuba
setup_lavapipe
