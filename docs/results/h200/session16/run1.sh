# Session 16 on the H200, run 1: the code as it stands (build-gpu/app/octrace)
# - accel_test on the GPU (BVH widths 0, 2, 4 against brute force);
# - octree against the BVH side by side on every family (`bench --accel
#   octree,bvh`): the sphere fields 488 / 8,000 / 128,000 / 1,000,000 at
#   r = 0.1, the balloon and the engine (1200x800, 10 spp, depth 50);
# - the 10M r = 0.01 field again with 9 repeats, with nvidia-smi sampling the
#   GPU's clocks, utilisation and throttle reasons every 100 ms beside it
#   (the bimodal timings of log 54's run 3).
# Carried: .gl, .gpub (bin.tgz), .assets. Prelude: tools/gpu_run.sh.
source tools/gpu_run.sh
nvidia-smi > "$R/smi_start.txt" 2>&1
nvidia-smi -q -d PERFORMANCE,CLOCK,COMPUTE > "$R/smi_q_start.txt" 2>&1
nvidia-smi --query-gpu=timestamp,utilization.gpu,utilization.memory,clocks.sm,clocks.mem,power.draw,temperature.gpu,clocks_throttle_reasons.active \
  --format=csv -lms 100 > "$R/smi_samples.csv" 2>&1 &
SMI=$!
export OCTRACE_TEST_DEVICE=gpu
suite accel_test 120
timeout 150 $B bench --device gpu --accel octree,bvh --spheres 488,8000,128000,1000000 --radius 0.1 \
  --csv "$R/spheres.csv" > "$R/spheres.log" 2>&1; echo "bench spheres rc=$?" >> "$T"
timeout 120 $B bench --device gpu --accel octree,bvh --scene .assets/balloon/scene.gltf,.assets/2CylinderEngine.glb \
  --csv "$R/meshes.csv" > "$R/meshes.log" 2>&1; echo "bench meshes rc=$?" >> "$T"
date -u +"%T.%3N start 10M" >> "$R/marks.txt"
timeout 200 $B bench --device gpu --accel octree,bvh --spheres 10000000 --radius 0.01 --repeat 9 \
  --csv "$R/s10m.csv" > "$R/s10m.log" 2>&1; echo "bench 10M r=0.01 rc=$?" >> "$T"
date -u +"%T.%3N end 10M" >> "$R/marks.txt"
kill $SMI
nvidia-smi -q -d PERFORMANCE,CLOCK > "$R/smi_q_end.txt" 2>&1
grep -h "ms (min" "$R/spheres.log" "$R/meshes.log" "$R/s10m.log" >> "$T"
grep -A3 "Processes" "$R/smi_start.txt" | tail -2 >> "$T"
gpu_finish
