# Session 26 on the H200, run 7 (expected.md): the kept form (pairs in the
# meshes' walk only) against bd2f5fc, and the GPU suites with it.
# Carried: .gl, .gpub (bin.txz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "base=BIN=$A" --variant "pairs=")
for sc in engine:.assets/2CylinderEngine.glb balloon:.assets/balloon/scene.gltf; do
  AB_ROUNDS=7 ab ${sc%%:*}_octree $S --scene ${sc#*:} --accel octree
  same_image ${sc%%:*}_octree $A $B $S --scene ${sc#*:} --accel octree
done
ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
timeout 90 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb > $OUT/meshes.log 2>&1
echo "bench meshes rc=$?" >> $T; grep -E "rays/s$" $OUT/meshes.log >> $T
gpu_suites
gpu_finish
