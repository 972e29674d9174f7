set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
R0=/tmp/ompi; mkdir -p $R0; for f in .mpi/*.deb; do dpkg -x $f $R0; done
export OPAL_PREFIX=$R0/usr PATH=$R0/usr/bin:$PATH LD_LIBRARY_PATH=$R0/usr/lib/x86_64-linux-gnu:$R0/usr/lib/x86_64-linux-gnu/openmpi/lib PMIX_MCA_pcompress_base_silence_warning=1
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nproc >> $R/date.txt
MPIRUN=$R0/usr/bin/orterun BATCH_MS=250 TURNS=auto timeout 480 tools/mpi_scaling.sh $B $R/mpi 5 > $R/mpi.log 2>&1; echo "mpi rc=$?"; grep -v "pmix\|dlopen\|Perhaps" $R/mpi.log | tail -60
find /tmp/res -name "*.png" -delete; find /tmp/res -name "*.accum" -delete; find /tmp/res -name "*.pfm" -delete; find /tmp/res -name "*.exr" -delete; tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
