# Session 29 on the H200, run 1 (expected.md): the walks' stacks partly in
# workgroup memory (sstack.patch, one binary, OCTRACE_SSTACK = N entries,
# 0 = f6d93d3's code), take_child (HEAD) against aed87eb, and the host's
# read-back and PNG write (logs 92, 94) against f6d93d3's. Carried: .gl,
# .gpub (bin.txz: COMMIT says which binary is which), .assets.
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
X=build-gpu/octrace-sst
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant "s0=BIN=$X OCTRACE_SSTACK=0" --variant "s4=BIN=$X OCTRACE_SSTACK=4" --variant "s8=BIN=$X OCTRACE_SSTACK=8" --variant "s16=BIN=$X OCTRACE_SSTACK=16")
ab peer_octree $P --accel octree
ab peer_bvh $P --accel bvh
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  ab ${sc%%:*}_octree $S --scene ${sc#*:} --accel octree
done
ab engine_bvh $S --scene .assets/2CylinderEngine.glb --accel bvh
AB_TIMEOUT=150 ab s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
OCTRACE_SSTACK=8 $X render $P --accel octree -q -o $R/a.pfm; $B render $P --accel octree -q -o $R/b.pfm
cmp -s $R/a.pfm $R/b.pfm && echo "peer octree s8/HEAD identical" >> $T || echo "peer octree s8/HEAD DIFFERENT" >> $T
OCTRACE_SSTACK=8 $X render $S --scene .assets/2CylinderEngine.glb --accel bvh -q -o $R/a.pfm; $B render $S --scene .assets/2CylinderEngine.glb --accel bvh -q -o $R/b.pfm
cmp -s $R/a.pfm $R/b.pfm && echo "engine bvh s8/HEAD identical" >> $T || echo "engine bvh s8/HEAD DIFFERENT" >> $T
rm -f $R/a.pfm $R/b.pfm
OCTRACE_SSTACK=8 $X render $P --accel octree --pipeline-stats -q -o $R/x.pfm > $R/stats_s8.txt 2>&1
grep -i "register\|shared\|local" $R/stats_s8.txt | head -6 | sed 's/^/s8: /' >> $T; rm -f $R/x.pfm
for m in readback write wall; do
  timeout 90 python3 tools/ab_render.py --octrace $B --rounds 5 --metric $m --render "$S -o $R/w.png" --variant "f6d93d3=BIN=$X" --variant "new=" --out $R/ab_host_$m.md > $R/ab_host_$m.log 2>&1
  echo "host $m rc=$?: $(grep -E '^\| (f6d93d3|new) ' $R/ab_host_$m.md | cut -d'|' -f2,5,6,7,9 | tr '\n' ' ')" >> $T
done
rm -f $R/w.png
V=(--variant "base=BIN=$A" --variant "head=")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  AB_ROUNDS=7 ab ${sc%%:*}_take_child $S --scene ${sc#*:} --accel octree
done
gpu_finish
