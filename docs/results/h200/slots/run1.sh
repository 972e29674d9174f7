# Log 52 (the stages of consecutive dispatches side by side, slots of
# the tail's buffers) at its final form, on the H200:
#   bash docs/results/h200/slots/run1.sh figures   # A/B against 70d7e3b, the peer side by side (both structures), GPU tests
#   bash docs/results/h200/slots/run1.sh suites    # the hard cases on the GPU
# Carried: .gl, .gpub (bin.tgz: app/octrace and tests/ = the change,
# octrace-base = 70d7e3b, COMMIT), .assets, .peers. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
case "${1:-figures}" in
figures)
  (cd .peers/karim && ./build.sh > $R/peer_build.txt 2>&1) &
  V=(--variant base=BIN=$A --variant slots=BIN=$B)
  P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
  ab peer_octree $P
  ab peer_bvh $P --accel bvh
  ab s488 --spheres 488 --radius 0.1 $S
  ab balloon --scene .assets/balloon/scene.gltf $S
  export OCTRACE_TEST_DEVICE=gpu
  suite accel_test 70
  timeout 120 build-gpu/tests/render_test --gtest_filter='*Staged*:*TailQueue*:*Batching*' > $R/render_test.txt 2>&1
  echo "render_test (staged, tail queue, batching) rc=$? $(grep -E '^\[  (PASSED|FAILED)' $R/render_test.txt | tr '\n' ' ')" >> $T
  suite effects_test 140
  unset OCTRACE_TEST_DEVICE
  wait
  timeout 100 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer --rounds 5 > $R/peer.log 2>&1; echo "peer rc=$?" >> $T; tail -4 $R/peer/peer_compare.md >> $T
  timeout 80 python3 tools/peer/compare.py --peer .peers/karim --octrace $B --out $R/peer_bvh --rounds 5 --octrace-args "--accel bvh" > $R/peer_bvh.log 2>&1; echo "peer --accel bvh rc=$?" >> $T; tail -4 $R/peer_bvh/peer_compare.md >> $T
  rm -f $R/peer*/*.ppm $R/peer*/*.pfm $R/peer*/*.png ;;
suites)
  export OCTRACE_TEST_DEVICE=gpu
  suite hardcases_test 420 ;;
esac
gpu_finish
