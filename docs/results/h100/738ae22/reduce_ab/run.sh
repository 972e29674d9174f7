set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
R0=/tmp/ompi; mkdir -p $R0; for f in .mpi/*.deb; do dpkg -x $f $R0; done
export OPAL_PREFIX=$R0/usr PATH=$R0/usr/bin:$PATH LD_LIBRARY_PATH=$R0/usr/lib/x86_64-linux-gnu:$R0/usr/lib/x86_64-linux-gnu/openmpi/lib PMIX_MCA_pcompress_base_silence_warning=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
B=build-gpu/app/octrace-x
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nproc >> $R/date.txt; lscpu | grep -E "Model name|NUMA node\(s\)|L3" >> $R/date.txt
for round in 0 1 2 3 4 5 6; do
  for combo in all:1 split:8 all:8 split:4 all:4; do
    OCTRACE_X_THREADS=${combo%:*} OCTRACE_X_GROUP=${combo#*:} timeout 60 $R0/usr/bin/orterun -q --oversubscribe --bind-to none -np 2 $B render --size 3840x2160 --spp 1 --json --quiet --out /tmp/merge.pfm > $R/$combo-$round.json 2>/dev/null
  done
done
python3 - <<'PY' | tee $R/summary.txt
import json, statistics as st
parts = ["reduce", "reduce_receive", "reduce_merge", "reduce_merge_wait", "reduce_send"]
print("interleaved rounds 1-6 (round 0 is the warm-up); median (min-max) ms")
print("| threads:group | " + " | ".join(parts) + " |")
for combo in ["all:1", "split:8", "all:8", "split:4", "all:4"]:
    v = {p: [] for p in parts}
    for r in range(1, 7):
        j = json.load(open(f"/tmp/res/{combo}-{r}.json"))["times_ms"]
        for p in parts: v[p].append(j[p])
    print(f"| {combo} | " + " | ".join(f"{st.median(v[p]):.1f} ({min(v[p]):.1f}-{max(v[p]):.1f})" for p in parts) + " |")
PY
tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
