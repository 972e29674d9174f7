# The ablation of expected.md on the H200, and the overlapped stages: throwaway
# builds of 70d7e3b with one difference from the CUDA peer taken out each
# (the patches here), A/B against the base build (octrace-base = 70d7e3b) on
# the peer's scene at its settings, with both structures; app/octrace is
# 70d7e3b with the stages of consecutive dispatches overlapped (slots of the
# tail's buffers; expected.md); flags of the base build; camera rays alone;
# the peer itself at depth 50 and 1.
# Carried: .gl, .gpub (bin.tgz), .peers (the CUDA peer). Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=170
(cd .peers/karim && ./build.sh > $R/peer_build.txt 2>&1) &
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant base=BIN=$A --variant overlap=BIN=$B)
for v in contract sphere notie rng nosum all; do V+=(--variant $v=BIN=build-gpu/octrace-$v); done
ab peer_octree $P
V+=(--variant peerwalk=BIN=build-gpu/octrace-peerwalk)
ab peer_bvh $P --accel bvh
V=(--variant base=BIN=$A --variant overlap=BIN=$B --variant tailoff="BIN=$A -- --tail-depth off"
   --variant tail3="BIN=$A -- --tail-depth 3" --variant lanes2="BIN=$A -- --sample-lanes 2"
   --variant spd4="BIN=$A -- --samples-per-dispatch 4" --variant ospd4="BIN=$B -- --samples-per-dispatch 4"
   --variant ospd2="BIN=$B -- --samples-per-dispatch 2")
ab flags_octree $P
ab flags_bvh $P --accel bvh
wait
for d in 50 1 50 1 50 1 50 1 50 1 50 1; do timeout 20 .peers/karim/karim_bench 1920 1080 64 $d 2>/dev/null | grep '^karim' >> $R/peer_depths.txt; done
echo "peer (6 processes each, depth 50 then 1):" >> $T; cut -d' ' -f2-6 $R/peer_depths.txt >> $T
V=(--variant base=BIN=$A --variant overlap=BIN=$B --variant all=BIN=build-gpu/octrace-all)
P1="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 1 --rr-depth 1 --device gpu"
ab depth1_octree $P1
ab depth1_bvh $P1 --accel bvh
for v in $A build-gpu/octrace-all build-gpu/octrace-peerwalk; do
  for a in octree bvh; do
    echo "$(basename $v) $a: $($v render $P --accel $a --pipeline-stats --json -q --out /tmp/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $R/pipeline_stats.txt
  done
done
cat $R/pipeline_stats.txt >> $T
for a in octree bvh; do for v in $A $B; do timeout 30 $v render $P --accel $a --size 480x270 -q --out /tmp/i_$(basename $v).pfm; done; echo "identity overlap $a: $(cmp /tmp/i_octrace-base.pfm /tmp/i_octrace.pfm && echo bit-identical)" >> $T; done
gpu_finish
