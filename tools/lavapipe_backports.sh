#!/usr/bin/env bash
# A newer lavapipe for Debian 12, beside the system's, for one process at a
# time:
#
#   tools/lavapipe_backports.sh [DIR]        (default DIR: .lavapipe-backports)
#   VK_ICD_FILENAMES=DIR/lvp_icd.json octrace render --device cpu ...
#
# Downloads mesa-vulkan-drivers from Debian's bookworm-backports archive (the
# official backports of later releases to Debian 12; on 2026-12-05 Mesa
# 25.0.7, built against Debian 12's LLVM 15), unpacks only its lavapipe into
# DIR and writes DIR/lvp_icd.json, which points the Vulkan loader at it. The
# system's driver, its packages and apt's sources are not touched (apt reads
# the backports index into a temporary folder). Then it checks that the
# unpacked driver loads: every symbol it needs is found in the system's
# libraries, and the loader lists its device.
#
# Why: Debian 12's own lavapipe (Mesa 22.3.6) turns every storage-buffer load
# of a shader into a loop over the vector's lanes (optimisation log 84); the
# backported one does not, and renders octrace's default scene in 0.6 of the
# time (log 88, docs/performance.md). To install it system-wide instead:
#
#   echo 'deb http://deb.debian.org/debian bookworm-backports main' \
#     > /etc/apt/sources.list.d/bookworm-backports.list
#   apt-get update && apt-get install -t bookworm-backports mesa-vulkan-drivers
#
# Needs apt-get, dpkg-deb and network access to deb.debian.org; root is not
# needed. DIR changes only once the unpacked driver has passed both checks.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$root/.lavapipe-backports}
keyring=/usr/share/keyrings/debian-archive-keyring.gpg
suite=bookworm-backports

fail() {
  echo "lavapipe_backports: $*" >&2
  exit 1
}
# Bad input: exit 2, before anything is downloaded.
[ $# -le 1 ] || { echo "lavapipe_backports: usage: tools/lavapipe_backports.sh [DIR]" >&2; exit 2; }
if [ -e "$dir" ] && [ ! -d "$dir" ]; then
  echo "lavapipe_backports: $dir: not a folder" >&2
  exit 2
fi
for tool in apt-get dpkg-deb; do
  command -v "$tool" >/dev/null || fail "$tool not found (this tool is for Debian 12)"
done
[ -r "$keyring" ] || fail "$keyring not found (Debian: debian-archive-keyring)"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lists/partial" "$work/cache/archives/partial"
echo "deb [signed-by=$keyring] http://deb.debian.org/debian $suite main" >"$work/sources.list"
apt_opts=(-o "Dir::Etc::SourceList=$work/sources.list" -o Dir::Etc::SourceParts=/dev/null
  -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache" -o Debug::NoLocking=1
  -o APT::Get::List-Cleanup=0)
# As root, apt would hand the download to its _apt user, who cannot write here.
if [ "$(id -u)" -eq 0 ]; then apt_opts+=(-o APT::Sandbox::User=root); fi
apt-get "${apt_opts[@]}" update -qq --error-on=any || fail "cannot read the $suite index from deb.debian.org"
(cd "$work" && apt-get "${apt_opts[@]}" download -qq "mesa-vulkan-drivers/$suite") ||
  fail "cannot download mesa-vulkan-drivers from $suite"
deb=$(ls "$work"/mesa-vulkan-drivers_*.deb)
version=$(dpkg-deb -f "$deb" Version)

dpkg-deb -x "$deb" "$work/root"
lib=$(find "$work/root" -name libvulkan_lvp.so | head -1)
[ -n "$lib" ] || fail "$deb holds no libvulkan_lvp.so"
api=$(sed -n 's/.*"api_version": *"\([^"]*\)".*/\1/p' "$(find "$work/root" -name 'lvp_icd*.json' | head -1)")
# The loader's manifest for a driver at $1.
manifest() {
  cat <<EOF
{
    "file_format_version": "1.0.0",
    "ICD": {
        "library_path": "$1",
        "api_version": "${api:-1.3.0}"
    }
}
EOF
}

# Every symbol the driver takes from other libraries must be in the system's
# versions of them (the package asks for newer libdrm than Debian 12's, but
# lavapipe calls none of what was added since).
if command -v nm >/dev/null; then
  missing=$(comm -23 \
    <(nm -D --undefined-only "$lib" | awk '$1 == "U" {sub(/@.*/, "", $2); print $2}' | sort -u) \
    <(ldd "$lib" | awk '/=>/ {print $3}' | xargs -r nm -D --defined-only 2>/dev/null |
      awk '{sub(/@.*/, "", $3); print $3}' | sort -u))
  [ -z "$missing" ] || fail "the driver needs symbols this system lacks: $(echo $missing | head -c 300)"
fi
if command -v vulkaninfo >/dev/null; then
  manifest "$lib" >"$work/lvp_icd.json"
  XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} VK_ICD_FILENAMES="$work/lvp_icd.json" vulkaninfo --summary 2>/dev/null |
    grep -q "llvmpipe" || fail "the Vulkan loader does not list the unpacked lavapipe"
fi

mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
# New files renamed over the old ones: a process still running the old
# driver keeps its copy (cp would rewrite the mapped file in place).
cp "$lib" "$dir/libvulkan_lvp.so.new"
mv -f "$dir/libvulkan_lvp.so.new" "$dir/libvulkan_lvp.so"
manifest "$dir/libvulkan_lvp.so" >"$dir/lvp_icd.json.new"
mv -f "$dir/lvp_icd.json.new" "$dir/lvp_icd.json"
echo "$version" >"$dir/VERSION"
echo "lavapipe_backports: Mesa $version in $dir"
echo "use: VK_ICD_FILENAMES=$dir/lvp_icd.json octrace render --device cpu ..."
