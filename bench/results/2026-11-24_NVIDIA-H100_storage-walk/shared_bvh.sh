#!/bin/bash
# shared_bvh.sh: BVH build records (bvh.* fields) of every shared scene, 3 repeats each
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for s in ${SCENES:-cornell-box veach-bidir veach-mis caustic-glass killeroos}; do
  f=$SC/$s/scene-v4.pbrt; [ -f $f ] || f=$(ls $SC/$s/*.pbrt | head -1)
  bench/cavalry_bench --bench $f --spp 1 --width 64 --height 64 --repeat 3 --json 2>/dev/null | grep '^{' > $OUT/$s.jsonl
  echo "$s $(wc -l < $OUT/$s.jsonl)"
done
