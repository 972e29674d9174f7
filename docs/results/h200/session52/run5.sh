# Session 52, run 5: `--tail-fetch on` where its auto is off (spheres
# alone), A/B against the auto: the goals' sphere fields with the octree
# and the BVH, and the peer's scene with the octree. Pack: run 3's (HEAD
# 0cad4c0). Carry .gl, .gpub, .assets. Expectations: expected.md, run 5.
source tools/gpu_run.sh
PEER="--scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu"
V=(--variant auto= --variant "on=-- --tail-fetch on")
for n in 488 8000 1000000; do for a in octree bvh; do
  AB_TIMEOUT=120 ab spheres${n}_$a $S --spheres $n --radius 0.1 --accel $a
done; done
AB_TIMEOUT=150 ab peer_octree $PEER --accel octree
echo "done at $(date -u +%T)" >> "$T"
gpu_finish
