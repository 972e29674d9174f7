# Session 55, run 3 (for the next session: no machine was lent after 01:58
# UTC): what the octree's and the BVH's leaf tests and child box tests
# cost on the H100, each done twice by a probe that leaves the image the
# same (optimisation log 159, which measured them on lavapipe):
# leaf2.patch (every top-level leaf reference tested twice), node2.patch
# (every child box loaded and tested twice: the octree's child loops, the
# BVH's binary node step). Pack: tools/gpu_pack.sh
# held=docs/results/h200/session55/held.patch
# pairs=docs/results/h200/session55/pairs.patch
# leaf2=docs/results/h200/session55/leaf2.patch
# node2=docs/results/h200/session55/node2.patch
# order2=docs/results/h200/session55/order2.patch (run 1's pack with
# three more probes; order2, the octree's child order and culling worked
# out twice, is a no-op for the BVH, its rows a check of the spread). Carry .gl, .gpub, .assets. Expectations: expected.md, run 3.
source tools/gpu_run.sh
L=build-gpu/octrace-leaf2
N=build-gpu/octrace-node2
O=build-gpu/octrace-order2
for a in octree bvh; do
  same_image "8000 $a leaf2" "$B" $L $S --spheres 8000 --radius 0.1 --accel $a
  same_image "8000 $a node2" "$B" $N $S --spheres 8000 --radius 0.1 --accel $a
done
same_image "8000 octree order2" "$B" $O $S --spheres 8000 --radius 0.1 --accel octree
V=(--variant head= --variant "leaf2=BIN=$L" --variant "node2=BIN=$N" --variant "order2=BIN=$O")
for n in 8000 488; do for a in octree bvh; do
  AB_TIMEOUT=120 ab marginal_${n}_$a $S --spheres $n --radius 0.1 --accel $a
done; done
for a in octree bvh; do walk_stats 8000_$a $S --spheres 8000 --radius 0.1 --accel $a; done
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
