# Session 29 on the H200, run 5 (expected.md, run 5): run 1's N = 0 of the
# shared-stack build (27.64 ms on the peer's scene, octree) against HEAD's
# binary (28.81 ms in run 2's peer comparison): an A/B in one run; and
# the read-back through one staging buffer (log 95) against 94fc5ce's.
# Carried: .gl, .gpub (bin.txz as run 1), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
X=build-gpu/octrace-sst
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant "head=" --variant "s0=BIN=$X OCTRACE_SSTACK=0")
ab peer_octree $P --accel octree
ab peer_bvh $P --accel bvh
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
ab balloon_octree $S --scene .assets/balloon/scene.gltf --accel octree
for v in head:$B s0:$X; do
  OCTRACE_SSTACK=0 ${v#*:} render $P --accel octree --pipeline-stats --json -q -o $R/x.pfm > $R/stats_${v%%:*}.json 2>&1
  python3 -c "import json; j=json.load(open('$R/stats_${v%%:*}.json')); print('${v%%:*}', {k: v for k, v in j.get('pipeline_statistics', {}).items() if 'egister' in k or 'hared' in k or 'ocal' in k or 'pill' in k})" >> $T 2>&1
done
rm -f $R/x.pfm
timeout 90 python3 tools/ab_render.py --octrace $B --rounds 5 --metric readback --render "$S -o $R/w.png" --variant "94fc5ce=" --variant "one_staging=BIN=build-gpu/octrace-rb" --out $R/ab_host_readback.md > $R/ab_host_readback.log 2>&1
echo "host readback rc=$?: $(grep -E '^\| (94fc5ce|one_staging) ' $R/ab_host_readback.md | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> $T
timeout 90 python3 tools/ab_render.py --octrace $B --rounds 5 --metric wall --render "$S -o $R/w.png" --variant "94fc5ce=" --variant "one_staging=BIN=build-gpu/octrace-rb" --out $R/ab_host_wall.md > $R/ab_host_wall.log 2>&1
echo "host wall rc=$?: $(grep -E '^\| (94fc5ce|one_staging) ' $R/ab_host_wall.md | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> $T
rm -f $R/w.png
gpu_finish
