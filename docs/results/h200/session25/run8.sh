# Session 25 on the H200, run 8 (expected.md): the engine's octree at
# --octree-refs 10 and 12 against the default 8. Carried: .gl, .gpub
# (run 6's bin.txz: app/octrace = 3075a2e), .assets. Prelude:
# tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "refs8=" --variant "refs10=-- --octree-refs 10" --variant "refs12=-- --octree-refs 12")
AB_ROUNDS=5 AB_TIMEOUT=80 ab engine_octree $S --scene .assets/2CylinderEngine.glb --accel octree
gpu_finish
