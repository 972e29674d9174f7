# Written at the end of session 12 (the device time was spent), run in
# session 13 with the peer under `--accel bvh` added: what log 49 still
# needs on the GPU. Two
# commands, each within the device's 10-minute limit:
#   bash docs/results/h200/tail/next_run4.sh figures   # peer side by side, bench series, meshes and BVH
#   bash docs/results/h200/tail/next_run4.sh suites    # the GPU suites with limits the three pipelines need
# Carried: .gl, .gpub (bin.tgz of the commit to measure, as run2), .assets,
# .peers (the CUDA peer). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
case "${1:-figures}" in
figures)
  (cd .peers/karim && ./build.sh > $R/peer_build.txt 2>&1) &
  wait
  timeout 150 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer --rounds 5 > $R/peer.log 2>&1; echo "peer rc=$?" >> $T; tail -4 $R/peer/peer_compare.md >> $T
  timeout 100 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --rounds 5 --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1; echo "peer --accel bvh rc=$?" >> $T; tail -4 $R/peer_bvh/peer_compare.md >> $T
  timeout 120 $B bench --device gpu --accel octree,bvh --spheres 488,8000,1000000,10000000 --radius 0.1 --csv $R/spheres.csv > $R/spheres.log 2>&1; echo "bench rc=$?" >> $T; tail -12 $R/spheres.log >> $T
  timeout 90 $B bench --device gpu -q --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --accel octree,bvh --repeat 5 --csv $R/meshes.csv > $R/meshes.md 2>&1; echo "meshes rc=$?" >> $T; cat $R/meshes.md >> $T
  rm -f $R/peer*/*.ppm $R/peer*/*.pfm $R/peer*/*.png ;;
suites)
  export OCTRACE_TEST_DEVICE=gpu
  timeout 420 build-gpu/tests/hardcases_test > $R/hardcases_test.txt 2>&1; echo "hardcases_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/hardcases_test.txt | tr '\n' ' ')" >> $T
  timeout 150 build-gpu/tests/effects_test > $R/effects_test.txt 2>&1; echo "effects_test rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/effects_test.txt | tr '\n' ' ')" >> $T ;;
esac
gpu_finish
