# After run 1 (summary in run1/): whether one sample per head invocation is
# what the camera rays lose against the peer. Binaries: octrace-base =
# 70d7e3b; app/octrace = overlap (run 1); octrace-headloop = overlap + each
# head invocation traces its pixel lane's samples one after another
# (headloop.patch; dispatch z = 1); octrace-all = run 1's every ablation.
# Flags: whole paths with one lane (--tail-depth off --sample-lanes 1: one
# invocation per pixel loops over the dispatch's samples, as the peer's
# threads do), the queue at bounce 1. Then the 10-spp scenes of the goals for
# overlap and headloop against base.
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=160
H=build-gpu/octrace-headloop
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --rr-depth 1 --device gpu"
V=(--variant base=BIN=$A --variant overlap=BIN=$B --variant headloop=BIN=$H
   --variant hl_lanes1="BIN=$H -- --sample-lanes 1" --variant hl_lanes2="BIN=$H -- --sample-lanes 2"
   --variant tail1="BIN=$B -- --tail-depth 1" --variant whole1="BIN=$B -- --tail-depth off --sample-lanes 1")
ab peer_octree $P --depth 50
ab peer_bvh $P --depth 50 --accel bvh
V+=(--variant all_whole1="BIN=build-gpu/octrace-all -- --tail-depth off --sample-lanes 1")
ab depth1_octree $P --depth 1
ab depth1_bvh $P --depth 1 --accel bvh
V=(--variant base=BIN=$A --variant overlap=BIN=$B --variant headloop=BIN=$H)
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
for v in $A $B $H; do
  for a in octree bvh; do
    echo "$(basename $v) $a: $($v render $P --depth 50 --accel $a --pipeline-stats --json -q --out /tmp/ps.png 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 300)" >> $T
  done
done
for sc in "--scene .assets/2CylinderEngine.glb --spp 10" "--scene .assets/balloon/scene.gltf --spp 10" "--scene tools/scenes/peer_field.json --spp 64 --rr-depth 1"; do
  for v in $A $H; do timeout 30 $v render $sc --size 480x270 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "identity headloop $sc: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace-headloop.pfm && echo bit-identical)" >> $T
done
gpu_finish
