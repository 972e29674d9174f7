# Prepared in session 34, for the next session with a GPU (after next1.sh):
# the BVH's top-level node cost again with 47 registers (a probe of HEAD
# reading it from OCTRACE_BVH_TOPCOST, topcost_env.patch; kept at 2 in log
# 112, where 3 was -0.2% on the peer's scene and +1.8% at 8,000 against 2),
# the tail queue's depth and step (flags), and `bench` at 10M spheres with
# the BVH (not run since session 33). Expectations: expected.md beside this
# script. Carried: .gl, .gpub, .assets.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
C=build-gpu/octrace-topcost
V=(--variant "cost2=" --variant "cost15=BIN=$C OCTRACE_BVH_TOPCOST=1.5" --variant "cost3=BIN=$C OCTRACE_BVH_TOPCOST=3"
   --variant "cost4=BIN=$C OCTRACE_BVH_TOPCOST=4")
AB_TIMEOUT=120 ab cost_peer_bvh $P --accel bvh
AB_TIMEOUT=60 ab cost_s488_bvh $S --spheres 488 --radius 0.1 --accel bvh
AB_TIMEOUT=60 ab cost_s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=150 ab cost_s1m_bvh $S --spheres 1000000 --radius 0.1 --accel bvh
V=(--variant "auto=" --variant "depth1=-- --tail-depth 1" --variant "depth3=-- --tail-depth 3" --variant "step2=-- --tail-step 2"
   --variant "off=-- --tail-depth off")
AB_TIMEOUT=150 ab tail_peer_octree $P --accel octree
AB_TIMEOUT=90 ab tail_engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
timeout 200 $B bench --device gpu --accel bvh --spheres 10000000 --radius 0.1 > $OUT/spheres10m.log 2>&1
echo "bench 10M rc=$?" >> $T; grep -E " ms" $OUT/spheres10m.log | grep -v '^#' | tail -3 >> $T
gpu_finish
