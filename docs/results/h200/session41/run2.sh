# Session 41 run2: which of run1's two autos (references 12, leaf 20)
# slows the uniform meshes (the 1M-triangle sheet, 400 instances of a 70k
# grid): each alone against the old autos, and leaf 20 alone on the engine.
# Pack: run1's. Carried: .gl, .gpub, .assets. Expectations in expected.md (run2).
source tools/gpu_run.sh
python3 tools/make_grid_glb.py 708 "$R/grid.glb" > /dev/null
python3 tools/make_grid_glb.py 187 "$R/grid400.glb" 400 > /dev/null
V=(--variant "old=-- --octree-refs 8 --octree-leaf 10" --variant "refs12=-- --octree-refs 12 --octree-leaf 10"
   --variant "leaf20=-- --octree-refs 8 --octree-leaf 20" --variant "both=-- --octree-refs 12 --octree-leaf 20")
AB_TIMEOUT=200 ab sheet $S --scene "$R/grid.glb" --accel octree
AB_TIMEOUT=200 ab grid400 $S --scene "$R/grid400.glb" --accel octree
AB_TIMEOUT=200 ab engine $S --scene .assets/2CylinderEngine.glb --accel octree
rm -f "$R/grid.glb" "$R/grid400.glb"
gpu_finish
