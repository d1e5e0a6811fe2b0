#!/bin/bash
# sweep.sh: SAH leaf constants on the H100, run from a staged build of main 4206d3e with
# sweep-env.patch applied (CAVALRY_BVH_COST_INNER / _COST_TRI / _MAX_LEAF become shader defines;
# CAVALRY_BVH_SAH_PARTS adds bvh.exp.* to the bench record). Not product code.
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C CAVALRY_STAGE_TIMES=1 CAVALRY_BVH_SAH_PARTS=1
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
T0=$(date +%s)
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
echo "gen $(( $(date +%s) - T0 )) s"
# warm the program cache (base constants) and the GPU
bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 16 --repeat 1 --json > $R/warm.jsonl 2>$R/warm.err
echo "warm $(( $(date +%s) - T0 )) s"
for c in ${COMBOS:-"1.2/8" "0.6/8" "2.0/8" "3.0/8" "1.2/4" "2.0/4" "3.0/16" "1.2/8"}; do
  ci=${c%/*}; ml=${c#*/}; tag=${ci}_${ml}; [ -e $R/g4_$tag.jsonl ] && tag=${tag}_b
  CAVALRY_BVH_COST_INNER=$ci CAVALRY_BVH_MAX_LEAF=$ml bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --json > $R/g4_$tag.jsonl 2>$R/g4_$tag.err
  grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*\|"render.traversal.closest_rays_per_s": [0-9.e+]*\|"render.traversal.shadow_rays_per_s": [0-9.e+]*' $R/g4_$tag.jsonl | paste - - - | sed "s/^/g4 $tag /"
  for s in ${SCENES:-veach-bidir}; do
    CAVALRY_BVH_COST_INNER=$ci CAVALRY_BVH_MAX_LEAF=$ml bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 1024 --repeat 3 --json > $R/${s}_$tag.jsonl 2>$R/${s}_$tag.err
    grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $R/${s}_$tag.jsonl | paste - - - | sed "s/^/$s $tag /"
  done
  echo "t $(( $(date +%s) - T0 )) s"
done
echo done
