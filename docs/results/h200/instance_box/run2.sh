# Log 48, second form (the box tested for instances in leaves only, not in
# the big list) on the H200: `render` A/B against 6ebd4af (5 rounds) on the
# meshes, identity, and `bench` of the meshes with both structures (the
# octree/BVH ratios and the glTF rays/s of the goals). Carried: .gl, .gpub
# (bin.tgz: app/octrace of the second form, octrace-base of f169de2 =
# 6ebd4af's code, COMMIT), .assets. The prelude is tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant base=BIN=$A --variant leaves=)
ab engine --scene .assets/2CylinderEngine.glb $S
ab balloon --scene .assets/balloon/scene.gltf $S
for sc in .assets/2CylinderEngine.glb .assets/balloon/scene.gltf; do for v in $A $B; do
  timeout 30 $v render --scene $sc --size 400x300 --spp 10 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "mesh identity $(basename $sc) octree 10 spp: $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical)" >> $T; done
timeout 80 $B bench --device gpu -q --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb --accel octree,bvh --repeat 5 --csv $R/bvh_meshes.csv > $R/bvh_meshes.md 2>&1; echo "bench rc=$?" >> $T; cat $R/bvh_meshes.md >> $T
gpu_finish
