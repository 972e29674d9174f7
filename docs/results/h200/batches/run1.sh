# Log 50 on the H200: `render` A/B of 50f606d (base) against fb, fb16 and
# fb32 (expected.md), 5 rounds, on the meshes, the sphere fields and the
# peer's scene; images of each variant against base; and `bench` of the
# engine again, 9 repeats (run 4 of log 49 had it at 18.9–76.5 ms).
# Carried: .gl, .gpub (bin.tgz: app/octrace = fb, octrace-base = 50f606d,
# octrace-fb16, octrace-fb32, COMMIT), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export AB_TIMEOUT=110
V=(--variant base=BIN=$A --variant fb=BIN=$B
   --variant fb16=BIN=build-gpu/octrace-fb16 --variant fb32=BIN=build-gpu/octrace-fb32)
ab balloon --scene .assets/balloon/scene.gltf $S
ab engine --scene .assets/2CylinderEngine.glb $S
ab s488 --spheres 488 --radius 0.1 $S
ab s8000 --spheres 8000 --radius 0.1 $S
ab peer --scene tools/scenes/peer_field.json --size 1920x1080 --spp 64 --depth 50 --rr-depth 1 --device gpu
for sc in "--scene .assets/2CylinderEngine.glb --spp 10" "--scene .assets/balloon/scene.gltf --spp 10" "--spheres 8000 --radius 0.1 --spp 10" "--scene tools/scenes/peer_field.json --spp 64 --rr-depth 1"; do
  for v in $A $B build-gpu/octrace-fb16 build-gpu/octrace-fb32; do timeout 30 $v render $sc --size 480x270 --device gpu -q --out /tmp/m_$(basename $v).pfm; done
  echo "identity $sc: fb $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace.pfm && echo bit-identical) fb16 $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace-fb16.pfm && echo bit-identical) fb32 $(cmp /tmp/m_octrace-base.pfm /tmp/m_octrace-fb32.pfm && echo bit-identical)" >> $T
done
timeout 90 $A bench --device gpu -q --scene .assets/2CylinderEngine.glb --accel octree,bvh --repeat 9 --csv $R/engine_bench.csv > $R/engine_bench.md 2>&1; echo "engine bench rc=$?" >> $T; cat $R/engine_bench.md >> $T
gpu_finish
