#!/bin/bash
# diag34.sh: renders, base (88fdad7, binary tree) against new (4-wide tree on the GPU), interleaved rounds, several renders per process
cd "$(dirname "$0")"
export LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
run() { local v=$1; shift; (cd $v && CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache_$v "$@"); }
new/bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
new/bench/gen_scene --triangles 4M --seed 1 --indirect --out /tmp/g4i >/dev/null 2>&1; fi=$(ls /tmp/g4i/*.pbrt | head -1)
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
for v in base new; do run $v bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 16 --repeat 1 >/dev/null 2>&1; done
for round in 1 2; do
  for v in base new; do
    run $v env CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4 --json > $R/g4s_${v}_$round.jsonl 2>$R/g4s_${v}_$round.err
    run $v env CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $fi --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4 --json > $R/g4is_${v}_$round.jsonl 2>$R/g4is_${v}_$round.err
    run $v bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 5 --json > $R/g4_${v}_$round.jsonl 2>$R/g4_${v}_$round.err
    for s in veach-bidir cornell-box; do run $v bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 1024 --repeat 3 --json > $R/${s}_${v}_$round.jsonl 2>$R/${s}_${v}_$round.err; done
    echo "r$round $v g4s first $(g render.traversal.first_bounce_rays_per_s $R/g4s_${v}_$round.jsonl)| sec $(g render.traversal.secondary_only_rays_per_s $R/g4s_${v}_$round.jsonl)| shadow $(g render.traversal.shadow_rays_per_s $R/g4s_${v}_$round.jsonl)"
    echo "r$round $v g4is first $(g render.traversal.first_bounce_rays_per_s $R/g4is_${v}_$round.jsonl)| sec $(g render.traversal.secondary_only_rays_per_s $R/g4is_${v}_$round.jsonl)"
    echo "r$round $v g4 64spp $(g render.time_to_spp_gpu_ms $R/g4_${v}_$round.jsonl)| veach $(g render.time_to_spp_gpu_ms $R/veach-bidir_${v}_$round.jsonl)| cornell $(g render.time_to_spp_gpu_ms $R/cornell-box_${v}_$round.jsonl)"
  done
done
tar -C $OUT -czf $OUT/diag34.tgz r && rm -rf $R
echo done
