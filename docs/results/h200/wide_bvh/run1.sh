# Log 54 on the H200, figures: the four-wide BVH (app/octrace, the working
# tree after fc632c6) A/B against the binary one (octrace-base = fc632c6),
# both with --accel bvh, 5 rounds, on the peer's scene, the 488- and
# 8000-sphere fields and the two meshes; images of both against each other;
# registers; the peer side by side with the wide BVH; the sphere series with
# both structures (the goals' bench command).
# Carried: .gl, .gpub (bin.tgz), .assets, .peers (the CUDA peer).
# Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=100
(cd .peers/karim && ./build.sh > $R/peer_build.txt 2>&1) &
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant base=BIN=$A --variant wide=BIN=$B)
ab peer_bvh $P --accel bvh
ab s488 --spheres 488 --radius 0.1 $S --accel bvh
ab s8000 --spheres 8000 --radius 0.1 $S --accel bvh
ab engine --scene .assets/2CylinderEngine.glb $S --accel bvh
ab balloon --scene .assets/balloon/scene.gltf $S --accel bvh
for sc in "--scene tools/scenes/peer_field.json --spp 64 --rr-depth 1" "--spheres 8000 --radius 0.1 --spp 10" "--scene .assets/2CylinderEngine.glb --spp 10" "--scene .assets/balloon/scene.gltf --spp 10"; do
  for v in $A $B; do timeout 30 $v render $sc --accel bvh --size 480x270 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "identity $sc: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T
done
for v in $A $B; do
  echo "$(basename $v) bvh: $($v render $P --accel bvh --pipeline-stats --json -q --out /tmp/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 600)" >> $R/pipeline_stats.txt
done
cat $R/pipeline_stats.txt >> $T
wait
timeout 100 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --rounds 5 --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1; echo "peer --accel bvh rc=$?" >> $T; tail -4 $R/peer_bvh/peer_compare.md >> $T
rm -f $R/peer*/*.ppm $R/peer*/*.pfm $R/peer*/*.png
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000,10000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1; echo "bench rc=$?" >> $T; tail -12 $R/spheres.log >> $T
gpu_finish
