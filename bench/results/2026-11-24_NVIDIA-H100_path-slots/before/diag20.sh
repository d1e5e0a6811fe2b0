#!/bin/bash
# diag20.sh: closest/any-hit rates on the 4M scene against the wavefront size (image size)
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
for wh in "640 360 64" "1280 720 64" "1920 1080 32" "2560 1440 16" "3840 2160 8"; do
  set -- $wh
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width $1 --height $2 --spp $3 --repeat 3 --json > $R/g4_$1.jsonl 2>$R/g4_$1.err
  grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*\|"render.secondary_rays_per_s": [0-9.e+]*\|"render.traversal.closest_rays_per_s": [0-9.e+]*\|"render.traversal.shadow_rays_per_s": [0-9.e+]*\|"render.passes": [0-9]*\|"render.iterations": [0-9]*' $R/g4_$1.jsonl | paste - - - - - - | sed "s/^/g4 $1x$2 /"
done
tar -C $OUT -czf $OUT/diag20.tgz r && rm -rf $R
echo done
