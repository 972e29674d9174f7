set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
B=build-gpu/app/octrace-x
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >> $R/date.txt
S="--size 1200x800 --spp 10 --depth 50 --device gpu"
ab() { name=$1; shift; timeout 100 python3 tools/ab_render.py --octrace $B --rounds 5 --render "$*" --variant "leaf10_cost2=" --variant "leaf4=-- --octree-leaf 4" --variant "leaf2=-- --octree-leaf 2" --variant "cost1=OCTRACE_X_NODE_COST=1" --variant "leaf4_cost1=OCTRACE_X_NODE_COST=1 -- --octree-leaf 4" --variant "leaf4_cost0.5=OCTRACE_X_NODE_COST=0.5 -- --octree-leaf 4" --out $R/ab_$name.md > $R/ab_$name.log 2>&1; echo "== $name"; tail -6 $R/ab_$name.md; }
{
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
} | tee $R/summary.txt
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
