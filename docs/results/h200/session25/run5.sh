# Session 25 on the H200, run 5 (expected.md): spatial splits in the
# meshes' BVH (log 75) against cd9c403, `bench` of the meshes, and the GPU
# suites with it. Carried: .gl, .gpub (bin.txz: app/octrace and tests = the
# change, octrace-base = cd9c403), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "new=")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  AB_ROUNDS=7 AB_TIMEOUT=100 ab ${sc%%:*}_bvh $S --scene ${sc#*:} --accel bvh
  same_image ${sc%%:*}_bvh $A $B $S --scene ${sc#*:} --accel bvh
done
AB_ROUNDS=5 AB_TIMEOUT=100 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
M="--device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb"
timeout 150 $B bench $M > $OUT/bench_meshes.txt 2>&1; echo "bench rc=$?" >> $T; grep -E "rays/s$" $OUT/bench_meshes.txt >> $T
gpu_suites
gpu_finish
