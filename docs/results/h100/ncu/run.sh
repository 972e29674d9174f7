set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt
which ncu nsys; ls -d /usr/local/cuda*/nsight-compute* /opt/nvidia/nsight-compute* 2>/dev/null
NCU=$(which ncu || ls /usr/local/cuda*/bin/ncu 2>/dev/null | head -1)
echo "ncu=$NCU"; $NCU --version 2>&1 | tail -2
$NCU --help 2>&1 | grep -i -E "vulkan|graphics|range|replay-mode" | head -20
timeout 120 $NCU --target-processes all --replay-mode application --app-replay-mode relaxed -c 1 --set basic $B render --scene tools/scenes/peer_field.json --size 640x360 --spp 4 --device gpu -q -o /tmp/x.png > $R/ncu_try.txt 2>&1; echo "rc=$?"; tail -30 $R/ncu_try.txt
tar czf $OUT/results.tgz -C /tmp res
