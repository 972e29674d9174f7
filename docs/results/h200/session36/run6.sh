# Session 36, run 6: runs 4-5 put the peer's lead in the head's segments
# (each 1.34x the peer's at depth 1 and 2; the values and the sum are not
# it: whole paths are no faster there). The machine code of today's BVH
# pipelines (the peer's scene; tools/nvidia_sass.py unpack, disasm and
# stats on the GPU machine, Debian's python3-zstandard carried in
# .sassdeb), to read against the peer's kernel
# (session17/run1/sass/peer_RenderKernel.sass.gz, the same peer code) and
# against session 19's reading (log 65). Carried: .gl, .gpub, .sassdeb.
source tools/gpu_run.sh
for f in .sassdeb/*.deb; do dpkg -x "$f" /; done
python3 -c "import zstandard" 2>> $T || echo "no zstandard module" >> $T
P0="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 320x180 --spp 8"
for a in bvh; do
  OCTRACE_DUMP_PIPELINE_CACHE=$R/cache_$a.bin timeout 60 $B render $P0 --accel $a -q -o $R/x.pfm --pipeline-stats --json > $R/render_$a.json 2> $R/render_$a.err
  python3 tools/nvidia_sass.py unpack $R/cache_$a.bin $R/sass_$a >> $T 2>&1
  python3 tools/nvidia_sass.py disasm $R/sass_$a --nvdisasm /usr/local/cuda/bin/nvdisasm >> $T 2>&1
  python3 tools/nvidia_sass.py stats $R/sass_$a/*.sass >> $T 2>&1
  rm -f $R/sass_$a/*.code $R/cache_$a.bin; gzip $R/sass_$a/*.sass
done
rm -f $R/x.pfm
gpu_finish
