# Session 37, run 4: run 3 at depth 1, 2 and 3: camera rays alone (depth 1) start outside every sphere, so a difference there would be a hit the culled tree misses, not a ray that started inside a neighbour
# (the pack bf6a716). Expectations:
# expected.md ("run4.sh").
source tools/gpu_run.sh
for d in 1 2 3; do
  for hp in keep cull; do
    "$B" render --size 1200x800 --spp 10 --depth $d --device gpu --spheres 1000000 --radius 0.1 --accel bvh \
      --hidden-parts $hp --json -q -o "$R/d${d}_$hp.pfm" > "$R/d${d}_$hp.json"
    python3 -c "import json; j=json.load(open('$R/d${d}_$hp.json')); b=j['bvh']; print('depth $d $hp: bvh depth', b['depth_reached'], 'walk', b['top_walk'], 'refs/leaf %.2f' % b['top_refs_per_leaf'])" >> "$T"
  done
  python3 - "$R/d${d}_keep.pfm" "$R/d${d}_cull.pfm" >> "$T" <<'PY'
import struct, sys
def pfm(p):
    with open(p, 'rb') as f:
        f.readline(); w, h = map(int, f.readline().split()); sc = float(f.readline()); d = f.read()
    return struct.unpack(('<' if sc < 0 else '>') + '%df' % (len(d) // 4), d)
a, b = pfm(sys.argv[1]), pfm(sys.argv[2])
diff = [i for i in range(len(a)) if a[i] != b[i]]
sa, sb = sum(a), sum(b)
big = max((abs(a[i] - b[i]) for i in diff), default=0.0)
print('%s vs %s: %d of %d values differ (%.4f%%), max |diff| %.3g, means %.6g / %.6g (rel %.2e)' % (
    sys.argv[1].split('/')[-1], sys.argv[2].split('/')[-1], len(diff), len(a), 100.0 * len(diff) / len(a), big, sa / len(a), sb / len(b), abs(sa - sb) / max(sb, 1e-30)))
PY
done
gpu_finish
