# Session 55, run 1: the checks of HEAD's render code on the GPU that
# session 54 left (its run 4: render_test's tail-fetch case under the
# auto of c720c39, the octree's from 1,000 spheres and the BVH's from
# 4,096; the hard cases at HEAD), and two of the octree's per-device
# choices measured again under today's walk: the nearest child held in
# registers (held.patch; log 60 chose the pushed form on GPUs in session
# 18, H200) and the leaf size over spheres (log 115 chose 24 in session
# 34). Pack: tools/gpu_pack.sh held=docs/results/h200/session55/held.patch
# pairs=docs/results/h200/session55/pairs.patch at HEAD (pairs added at
# 02:08 UTC, after the machines stopped coming: the top level's node step
# two children a trip, log 81's form for the meshes). Carry .gl, .gpub, .assets. Expectations: expected.md, run 1.
# The engine's A/B dropped before the run (01:47 UTC): three starts failed
# and the device time left must hold runs 1 and 2.
source tools/gpu_run.sh
H=build-gpu/octrace-held
P=build-gpu/octrace-pairs
render_cases '*TailFetch*:*PathsCutShort*' 200
same_image "8000 octree held" "$B" $H $S --spheres 8000 --radius 0.1 --accel octree
same_image "8000 octree pairs" "$B" $P $S --spheres 8000 --radius 0.1 --accel octree
V=(--variant head= --variant "held=BIN=$H" --variant "pairs=BIN=$P")
ab spheres8000_octree $S --spheres 8000 --radius 0.1 --accel octree
ab spheres488_octree $S --spheres 488 --radius 0.1 --accel octree
ab spheres1m_octree $S --spheres 1000000 --radius 0.1 --accel octree
V=(--variant auto= --variant "leaf16=-- --octree-leaf 16" --variant "leaf32=-- --octree-leaf 32")
ab leaf_spheres8000_octree $S --spheres 8000 --radius 0.1 --accel octree
hardcases_shards 8 330
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
