set -u; rm -rf build-gpu; mkdir build-gpu; tar xzf .gpub/bin.tgz -C build-gpu
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export XDG_RUNTIME_DIR=/tmp
R0=/tmp/ompi; mkdir -p $R0; for f in .mpi/*.deb; do dpkg -x $f $R0; done
B=build-gpu/app/octrace
$B devices >/dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/res; mkdir -p $R; date -u > $R/date.txt; cat build-gpu/COMMIT >> $R/date.txt; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >> $R/date.txt
timeout 200 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer --rounds 5 > $R/peer.log 2>&1; echo "peer rc=$?"; cat $R/peer/peer_compare.md | tail -6
timeout 90 $B bench --device gpu --accel octree,bvh --spheres 488,8000,128000,1000000 --radius 0.1 --csv $R/bvh_spheres.csv > $R/bvh_spheres.md 2>$R/bvh.log; cat $R/bvh_spheres.md | tail -10
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --csv $R/bvh_meshes.csv > $R/bvh_meshes.md 2>> $R/bvh.log; cat $R/bvh_meshes.md | tail -6
(export OPAL_PREFIX=$R0/usr PATH=$R0/usr/bin:$PATH LD_LIBRARY_PATH=$R0/usr/lib/x86_64-linux-gnu:$R0/usr/lib/x86_64-linux-gnu/openmpi/lib PMIX_MCA_pcompress_base_silence_warning=1
MPIRUN=$R0/usr/bin/orterun BATCH_MS=250 TURNS=auto REDUCE=shared timeout 200 tools/mpi_scaling.sh $B $R/mpi 5 > $R/mpi.log 2>&1; echo "mpi rc=$?"; grep -A3 "^| ranks |\|^| reduce ms" $R/mpi.log | head -14)
rm -f $R/peer/*.ppm $R/peer/*.pfm $R/peer/*.png; find /tmp/res -name "*.pfm" -delete; find /tmp/res -name "*.accum" -delete; tar czf $OUT/results.tgz -C /tmp res; ls -la $OUT
