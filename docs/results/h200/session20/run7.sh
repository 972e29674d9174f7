# Session 20 on the H200, run 7 (expected.md): the balloon with tail levels
# of steps 1, 4, 16 and 47 against one tail (1cd8391's auto with triangles).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
V=(--variant "one=" --variant "s47=-- --tail-step 47" --variant "s16=-- --tail-step 16" --variant "s4=-- --tail-step 4" --variant "s1=-- --tail-step 1")
AB_TIMEOUT=80 ab balloon_octree $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
