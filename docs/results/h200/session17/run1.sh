# Session 17 on the H200, run 1: the machine code NVIDIA's Vulkan driver
# builds from octrace's pipelines, beside the CUDA peer's (log 58).
# A throwaway build (sass_dump.patch: OCTRACE_DUMP_PIPELINE_CACHE=FILE writes
# vkGetPipelineCacheData at exit) renders the peer's scene once per
# structure; nvdisasm reads the blobs as raw SM90 code at each of the 16
# byte shifts, and the shift whose text has the most real instructions is
# kept. The peer's kernel: cuobjdump -sass.
# Carried: .gl, .gpub (bin.tgz), .peers/karim. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
ND=$(command -v nvdisasm || ls /usr/local/cuda*/bin/nvdisasm 2>/dev/null | head -1)
CO=$(command -v cuobjdump || ls /usr/local/cuda*/bin/cuobjdump 2>/dev/null | head -1)
echo "nvdisasm: $ND ($($ND --version | tail -1))" >> "$T"
mkdir -p "$R/glcache"
for a in bvh octree; do
  __GL_SHADER_DISK_CACHE_PATH=$R/glcache __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 \
  OCTRACE_DUMP_PIPELINE_CACHE=$R/cache_$a.bin timeout 60 $B render --scene tools/scenes/peer_field.json \
    --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu --accel $a -o $R/$a.png --json -q \
    --pipeline-stats > $R/render_$a.json 2> $R/render_$a.err
  echo "$a rc=$? cache $(stat -c %s $R/cache_$a.bin 2>/dev/null) bytes" >> "$T"
done
find $R/glcache -type f -printf '%s %p\n' >> "$T"
python3 - "$ND" "$R" >> "$T" 2>&1 <<'PY'
import subprocess, sys, os, re, glob
nd, r = sys.argv[1], sys.argv[2]
good = re.compile(r'\b(FFMA|FMNMX|LDG|ISETP|FSETP|IMAD|STL|LDL|BRA|FADD|FMUL|MOV|SEL|LOP3|IADD3)\b')
blobs = [os.path.join(r, f) for f in ("cache_bvh.bin", "cache_octree.bin")]
blobs += sorted(p for p in glob.glob(os.path.join(r, "glcache", "**", "*"), recursive=True) if os.path.isfile(p))
for b in blobs:
    data = open(b, "rb").read()
    best = None
    for k in range(16):
        n = (len(data) - k) // 16 * 16
        if n <= 0: continue
        p = "/tmp/shift.bin"
        open(p, "wb").write(data[k:k + n])
        out = subprocess.run([nd, "-b", "SM90", p], capture_output=True, text=True).stdout
        score = len(good.findall(out))
        if best is None or score > best[0]: best = (score, k, out)
    if best:
        name = os.path.relpath(b, r).replace("/", "_")
        open(os.path.join(r, f"sass_{name}_k{best[1]}.txt"), "w").write(best[2])
        print(f"{name}: {len(data)} bytes, best shift {best[1]}, {best[0]} instruction words")
PY
(cd .peers/karim && ./build.sh > $R/peer_build.log 2>&1 && $CO -sass karim_bench > $R/peer.sass 2>&1; echo "peer sass rc=$? $(wc -l < $R/peer.sass) lines" >> "$T")
gpu_finish
