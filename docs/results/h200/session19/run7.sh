# Session 19 on the H200, run 7: the machine code of the kept BVH pipelines
# (the peer's scene, --accel bvh; tools/nvidia_sass.py unpack, disasm and
# stats on the GPU machine, with Debian's python3-zstandard carried in
# .sassdeb), to compare the binary walk's steps with the peer's kernel
# (session17/run1/sass/peer_RenderKernel.sass.gz, the same peer code).
# Carried: .gl, .gpub (bin.tgz), .sassdeb. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
for f in .sassdeb/*.deb; do dpkg -x "$f" /; done
python3 -c "import zstandard" 2>> $T || echo "no zstandard module" >> $T
P0="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 320x180 --spp 8"
for a in bvh octree; do
  OCTRACE_DUMP_PIPELINE_CACHE=$R/cache_$a.bin timeout 60 $B render $P0 --accel $a -q -o $R/x.pfm --pipeline-stats --json > $R/render_$a.json 2> $R/render_$a.err
  python3 tools/nvidia_sass.py unpack $R/cache_$a.bin $R/sass_$a >> $T 2>&1
  python3 tools/nvidia_sass.py disasm $R/sass_$a --nvdisasm /usr/local/cuda/bin/nvdisasm >> $T 2>&1
  python3 tools/nvidia_sass.py stats $R/sass_$a/*.sass >> $T 2>&1
  rm -f $R/sass_$a/*.code $R/cache_$a.bin; gzip $R/sass_$a/*.sass
done
rm -f $R/x.pfm
gpu_finish
