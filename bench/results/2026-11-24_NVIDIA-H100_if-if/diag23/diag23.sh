#!/bin/bash
# diag23.sh: intersect rate by iteration (wave size) on the 4M scene, open and --indirect
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
bench/gen_scene --triangles 4M --seed 1 --indirect --out /tmp/g4i >/dev/null 2>&1; fi=$(ls /tmp/g4i/*.pbrt | head -1)
bench/cavalry_bench --bench $f --width 640 --height 360 --spp 4 --repeat 1 >/dev/null 2>&1
run() { n=$1; shift; CAVALRY_STAGE_TIMES=1 bench/cavalry_bench "$@" --json > $R/$n.jsonl 2>$R/$n.err
  echo "$n ms $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $R/$n.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$n sec-only $(grep -o '"render.traversal.secondary_only_rays_per_s": [0-9.e+]*' $R/$n.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$n first-bounce $(grep -o '"render.traversal.first_bounce_rays_per_s": [0-9.e+]*' $R/$n.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$n closest $(grep -o '"render.traversal.closest_rays_per_s": [0-9.e+]*' $R/$n.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$n shadow $(grep -o '"render.traversal.shadow_rays_per_s": [0-9.e+]*' $R/$n.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  grep "intersect iteration" $R/$n.err | tail -n 40 | head -12; }
run g4s_k4 --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4
run g4s_k8 --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 8 --paths-per-pixel 8
run g4is_k4 --bench $fi --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4
run g4i --bench $fi --width 1280 --height 720 --spp 64 --repeat 3
run g4s_2560 --bench $f --width 2560 --height 1440 --spp 16 --repeat 3 --pass-spp 1 --paths-per-pixel 1
tar -C $OUT -czf $OUT/diag23.tgz r && rm -rf $R
echo done
