cd /work/main; export XDG_RUNTIME_DIR=/tmp
for sc in f1m f1m_noglass; do for hp in keep cull; do
  /usr/bin/time -f "$sc $hp %e s" build/app/octrace render --size 1200x800 --spp 16 --depth 8 --device cpu --scene /tmp/dbg/$sc.json --accel bvh --hidden-parts $hp -q -o /tmp/dbg/g16_${sc}_$hp.pfm
done; done
/usr/bin/python3 /tmp/pfm.py /tmp/dbg/g16_f1m_keep.pfm /tmp/dbg/g16_f1m_cull.pfm
/usr/bin/python3 /tmp/pfm.py /tmp/dbg/g16_f1m_noglass_keep.pfm /tmp/dbg/g16_f1m_noglass_cull.pfm
