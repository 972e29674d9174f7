# Log 126's trees (the octree over the spheres' surfaces) against a002be6's
# (before_log126.patch), the 1M field as generated and without glass
# (noglass.cpp's JSON files), 1200x800, 16 spp, depth 8, the octree.
# BEFORE / AFTER: the two binaries.
export XDG_RUNTIME_DIR=/tmp
for sc in f1m f1m_noglass; do for v in before after; do
  bin=$BEFORE; [ $v = after ] && bin=$AFTER
  "$bin" render --size 1200x800 --spp 16 --depth 8 --device cpu --scene /tmp/dbg/$sc.json --accel octree -q -o /tmp/dbg/o16_${sc}_$v.pfm
done; python3 pfm.py /tmp/dbg/o16_${sc}_before.pfm /tmp/dbg/o16_${sc}_after.pfm > /tmp/dbg/o16_$sc.txt; head -1 /tmp/dbg/o16_$sc.txt; done
