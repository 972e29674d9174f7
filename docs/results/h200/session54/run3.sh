# Session 54, run 3: the tail fetch's auto per structure (c720c39: the
# octree from 1,000 spheres, the BVH from 8,000, from run 2's sweep):
# render_test's tail-fetch case on the GPU (its octree field of 1,100
# spheres and BVH field of 8,100 under the auto, the same bits as with the
# fetch off; the BVH off at 1,100), and the auto against the former auto
# (4,096 for both) where they differ: 1,000 and 2,000 spheres with the
# octree (now on; `--tail-fetch off` was the former auto), 6,000 with the
# BVH (now off; `on` was the former). Pack: tools/gpu_pack.sh at c720c39.
# Carry .gl, .gpub, .assets. Expectations: expected.md, run 3.
source tools/gpu_run.sh
render_cases '*TailFetch*' 200
V=(--variant "auto=" --variant "former=-- --tail-fetch off")
for n in 1000 2000; do ab spheres${n}_octree $S --spheres $n --radius 0.1 --accel octree; done
V=(--variant "auto=" --variant "former=-- --tail-fetch on")
ab spheres6000_bvh $S --spheres 6000 --radius 0.1 --accel bvh
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
