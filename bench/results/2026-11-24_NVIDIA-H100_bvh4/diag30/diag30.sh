#!/bin/bash
# diag30.sh: 4-wide tree (branch bvh4, CAVALRY_BVH4_EXPERIMENT=1, vars/w4) against the binary tree (vars/base), one repeat per process (later repeats of a w4 process ran slow, diag29)
cd "$(dirname "$0")"
export CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
bench/gen_scene --triangles 4M --seed 1 --indirect --out /tmp/g4i >/dev/null 2>&1; fi=$(ls /tmp/g4i/*.pbrt | head -1)
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
for v in base w4; do CAVALRY_DATA_DIR=$PWD/vars/$v bench/cavalry_bench --bench $SC/cornell-box/scene-v4.pbrt --spp 16 --repeat 1 >/dev/null 2>&1; done
for round in 1 2 3; do
for v in base w4; do
  export CAVALRY_DATA_DIR=$PWD/vars/$v
  if [ $v = w4 ]; then export CAVALRY_BVH4_EXPERIMENT=1; else unset CAVALRY_BVH4_EXPERIMENT; fi
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 1 --pass-spp 4 --json > $R/g4s_${v}_$round.jsonl 2>$R/g4s_${v}_$round.err
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $fi --width 1280 --height 720 --spp 64 --repeat 1 --pass-spp 4 --json > $R/g4is_${v}_$round.jsonl 2>$R/g4is_${v}_$round.err
  bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 1 --json > $R/g4_${v}_$round.jsonl 2>$R/g4_${v}_$round.err
  bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 1024 --repeat 1 --json > $R/veach_${v}_$round.jsonl 2>$R/veach_${v}_$round.err
  bench/cavalry_bench --bench $SC/cornell-box/scene-v4.pbrt --spp 1024 --repeat 1 --json > $R/cornell_${v}_$round.jsonl 2>$R/cornell_${v}_$round.err
  echo "$v r$round g4s first-bounce $(g render.traversal.first_bounce_rays_per_s $R/g4s_${v}_$round.jsonl) sec-only $(g render.traversal.secondary_only_rays_per_s $R/g4s_${v}_$round.jsonl) camera $(g render.traversal.camera_only_rays_per_s $R/g4s_${v}_$round.jsonl) shadow $(g render.traversal.shadow_rays_per_s $R/g4s_${v}_$round.jsonl)"
  echo "$v r$round g4is first-bounce $(g render.traversal.first_bounce_rays_per_s $R/g4is_${v}_$round.jsonl) sec-only $(g render.traversal.secondary_only_rays_per_s $R/g4is_${v}_$round.jsonl) shadow $(g render.traversal.shadow_rays_per_s $R/g4is_${v}_$round.jsonl)"
  echo "$v r$round g4 $(g render.time_to_spp_gpu_ms $R/g4_${v}_$round.jsonl) | veach $(g render.time_to_spp_gpu_ms $R/veach_${v}_$round.jsonl) | cornell $(g render.time_to_spp_gpu_ms $R/cornell_${v}_$round.jsonl)"
done
done
for v in base w4; do for s in g4s g4is; do echo "$v $s"; grep "intersect iteration" $R/${s}_${v}_3.err | head -n 9; done; done
tar -C $OUT -czf $OUT/diag30.tgz r && rm -rf $R
echo done
