# Session 50 run2, right after run1 on the same warm H100 (the 3 minutes of
# device time left): the balloon's and the peer's scene's passes dispatch
# by dispatch. Run as one command line; here as it ran, with its lines
# split.
source tools/gpu_run.sh >/dev/null 2>&1
for a in "balloon|$S --scene .assets/balloon/scene.gltf --accel octree" \
         "peer_bvh|--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu --accel bvh"; do
  n=${a%%|*}; r=${a#*|}
  timeout 50 python3 tools/dispatch_table.py --octrace "$B" --render "$r" --out "$OUT/dispatch_$n.md" > /dev/null 2>&1
  echo "$n rc=$?"
done
cat $OUT/*.md
