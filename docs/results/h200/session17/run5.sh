# Session 17 on the H200, run 5: more of the suite on the GPU at the kept
# code of d168363 (pipelines without the driver's bounds checks, log 58):
# every Vulkan suite but those run 3 ran, all at once (the GPU shared), each
# within 75 s. Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
export OCTRACE_TEST_DEVICE=gpu
mkdir -p build-gpu/tests/tmp
for t in effects_test render_test texture_test envmap_render_test gltf_test golden_test gpu_scene_test big_scene_test interrupt_test; do
  timeout 75 build-gpu/tests/$t > $R/$t.txt 2>&1 &
done
wait
for t in effects_test render_test texture_test envmap_render_test gltf_test golden_test gpu_scene_test big_scene_test interrupt_test; do
  echo "$t: $(grep -E '^\[  (PASSED|FAILED|SKIPPED)' $R/$t.txt | tr '\n' ' ') $(tail -1 $R/$t.txt | cut -c1-80)" >> $T
done
gpu_finish
