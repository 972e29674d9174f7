# Session 23 on the H200, run 6 (expected.md): --samples-per-dispatch on the
# peer's scene and 8,000 spheres. Carried: .gl, .gpub (run 5's bin.txz),
# .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
P="--scene tools/scenes/peer_field.json --depth 50 --rr-depth 1 --device gpu --size 1920x1080 --spp 64"
V=(--variant "d7=" --variant "d4=-- --samples-per-dispatch 4" --variant "d5=-- --samples-per-dispatch 5" --variant "d6=-- --samples-per-dispatch 6")
AB_TIMEOUT=150 ab peer_bvh $P --accel bvh
V=(--variant "d10=" --variant "d5=-- --samples-per-dispatch 5")
AB_TIMEOUT=60 ab s8000_bvh $S --spheres 8000 --radius 0.1 --accel bvh
AB_TIMEOUT=60 ab s8000_octree $S --spheres 8000 --radius 0.1 --accel octree
gpu_finish
