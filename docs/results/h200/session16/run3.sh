# Session 16 on the H200, run 3 (log 55): bench's warm-up of at least
# --warmup seconds (default 0.5) against the one-run warm-up (--warmup 0),
# with nvidia-smi sampling clocks every 100 ms beside it; and whether a
# one-render process (tools/ab_render.py, tools/peer/compare.py) starts at a
# low clock: the peer's scene with the BVH, 5 renders back to back, then 5
# renders each after 5 s of idle.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
nvidia-smi --query-gpu=timestamp,utilization.gpu,clocks.sm,power.draw,clocks_throttle_reasons.active \
  --format=csv -lms 100 > "$R/smi_samples.csv" 2>&1 &
SMI=$!
mark() { date -u +"%T.%3N $*" >> "$R/marks.txt"; }
M=.assets/balloon/scene.gltf,.assets/2CylinderEngine.glb
for w in 0.5 0; do
  mark "meshes warmup $w"
  timeout 120 $B bench --device gpu --accel octree,bvh --scene $M --warmup $w --csv "$R/meshes_w$w.csv" \
    > "$R/meshes_w$w.log" 2>&1; echo "bench meshes --warmup $w rc=$?" >> "$T"
  grep "rays/s" "$R/meshes_w$w.log" | grep -v "^|\|Device" >> "$T"
done
mark "10M"
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 10000000 --radius 0.01 --repeat 9 \
  --csv "$R/s10m.csv" > "$R/s10m.log" 2>&1; echo "bench 10M r=0.01 rc=$?" >> "$T"
grep "ms (min" "$R/s10m.log" >> "$T"
P="render --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --accel bvh --device gpu -q --json --out /tmp/p.png"
one() { timeout 30 $B $P 2>/dev/null | python3 -c "import json,sys; print('%.2f' % json.load(sys.stdin)['times_ms']['render'])"; }
mark "peer back to back"
echo "peer scene, bvh, back to back: $(for i in 1 2 3 4 5 6; do one; done | paste -sd' ')" >> "$T"
mark "peer after 5 s idle"
echo "peer scene, bvh, each after 5 s idle: $(for i in 1 2 3 4 5; do sleep 5; one; done | paste -sd' ')" >> "$T"
mark end
kill $SMI
gpu_finish
