#!/bin/bash
# diag10.sh: does the renderer's traversal fall off with scene size as bvh_bench's rays do?
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
for t in 1M 4M 8M 16M; do
  bench/gen_scene --triangles $t --seed 1 --out /tmp/g$t >/dev/null 2>&1; f=$(ls /tmp/g$t/*.pbrt | head -1)
  CAVALRY_STAGE_TIMES=1 timeout 200 bench/cavalry_bench --bench $f --width 640 --height 360 --spp 16 --repeat 2 --json > $OUT/r_$t.jsonl 2>$OUT/r_$t.err
  echo "$t: $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*\|"render.traversal.closest_rays_per_s": [0-9.e+]*\|"render.traversal.shadow_rays_per_s": [0-9.e+]*\|"bvh.mb": [0-9.e+]*' $OUT/r_$t.jsonl | tail -4 | tr '\n' ' ')"
  rm -rf /tmp/g$t
done
