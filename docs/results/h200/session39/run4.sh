# Session 39 run4: where the whole process of `render` goes for the dense
# fields at its defaults (1200x800, 10 spp, depth 50), on the H100: each of
# 1M and 10M spheres (r = 0.1) with each structure, one warm-up and 4 runs,
# `render --json`'s times_ms (the stages, in order) and the whole process's
# wall time, medians. The pack 0289451 (the session's code but log 128, a
# faster clip in the octree's build that these defaults do not run).
# Carried: .gl, .gpub.
source tools/gpu_run.sh
for n in 1000000 10000000; do
  for accel in octree bvh; do
    for i in 0 1 2 3 4; do
      t0=$(date +%s%N)
      "$B" render $S --spheres $n --radius 0.1 --accel $accel --json -q -o "$R/x.png" > "$R/times_${n}_${accel}_$i.json" 2>&1
      echo "$(( ($(date +%s%N) - t0) / 1000000 ))" > "$R/wall_${n}_${accel}_$i.txt"
    done
  done
done
rm -f "$R/x.png"
python3 - "$R" >> "$T" <<'PY'
import json, statistics, sys, glob
r = sys.argv[1]
keys = ["device_init", "scene", "accel_build", "upload", "pipeline", "render", "readback", "write"]
print("| spheres | accel | wall s | " + " | ".join(keys) + " | hidden_parts ms |")
print("|---|---|---:|" + "---:|" * (len(keys) + 1))
for n in ("1000000", "10000000"):
    for accel in ("octree", "bvh"):
        runs = [json.load(open(f"{r}/times_{n}_{accel}_{i}.json")) for i in range(1, 5)]
        wall = statistics.median(float(open(f"{r}/wall_{n}_{accel}_{i}.txt").read()) / 1000 for i in range(1, 5))
        med = {k: statistics.median(d["times_ms"][k] for d in runs) for k in keys}
        hp = statistics.median(d["hidden_parts"]["ms"] for d in runs)
        print(f"| {n} | {accel} | {wall:.2f} | " + " | ".join(f"{med[k]:.1f}" for k in keys) + f" | {hp:.1f} |")
PY
gpu_finish
