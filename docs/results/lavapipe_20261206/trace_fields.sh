cd /work/main; export XDG_RUNTIME_DIR=/tmp
K=$1; s=$2; f=$3
for hp in keep cull; do
  code=$((1000 + 3*s + f))
  build/app/octrace render --size 1200x800 --spp 2 --depth $K --rr-depth $code --device cpu --spheres 1000000 --radius 0.1 --accel bvh --hidden-parts $hp -q -o /tmp/dbg/k${K}_s${s}_f${f}_$hp.pfm
done
