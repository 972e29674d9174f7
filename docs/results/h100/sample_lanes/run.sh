set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
ab() { name=$1; shift; timeout 100 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" --variant "auto=" --variant "lanes1=-- --sample-lanes 1" --variant "lanes2=-- --sample-lanes 2" --variant "lanes8=-- --sample-lanes 8" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "== $name"; tail -4 $R/ab_$name.md; }
{
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab s128k --spheres 128000 --radius 0.1 $S
ab s1m --spheres 1000000 --radius 0.1 $S
} | tee $R/summary.txt
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
