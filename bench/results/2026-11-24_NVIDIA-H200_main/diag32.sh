#!/bin/bash
# diag32.sh: main (binary tree) on an H200: 4 M scene and closed room with passes of 4 spp (one render per process), 64 spp, veach-bidir and cornell-box at 1024 spp
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
bench/gen_scene --triangles 4M --seed 1 --indirect --out /tmp/g4i >/dev/null 2>&1; fi=$(ls /tmp/g4i/*.pbrt | head -1)
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 1 --pass-spp 4 >/dev/null 2>&1
for round in 1 2 3; do
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 1 --pass-spp 4 --json > $R/g4s_$round.jsonl 2>$R/g4s_$round.err
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $fi --width 1280 --height 720 --spp 64 --repeat 1 --pass-spp 4 --json > $R/g4is_$round.jsonl 2>$R/g4is_$round.err
  echo "r$round g4s first-bounce $(g render.traversal.first_bounce_rays_per_s $R/g4s_$round.jsonl) sec-only $(g render.traversal.secondary_only_rays_per_s $R/g4s_$round.jsonl) shadow $(g render.traversal.shadow_rays_per_s $R/g4s_$round.jsonl)"
  echo "r$round g4is first-bounce $(g render.traversal.first_bounce_rays_per_s $R/g4is_$round.jsonl) sec-only $(g render.traversal.secondary_only_rays_per_s $R/g4is_$round.jsonl) shadow $(g render.traversal.shadow_rays_per_s $R/g4is_$round.jsonl)"
done
bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 5 --json > $R/g4.jsonl 2>$R/g4.err
for s in veach-bidir cornell-box; do bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 1024 --repeat 5 --json > $R/$s.jsonl 2>$R/$s.err; done
echo "g4 64spp $(g render.time_to_spp_gpu_ms $R/g4.jsonl) | veach $(g render.time_to_spp_gpu_ms $R/veach-bidir.jsonl) | cornell $(g render.time_to_spp_gpu_ms $R/cornell-box.jsonl)"
for s in g4s g4is; do echo "$s"; grep "intersect iteration" $R/${s}_3.err | head -n 6; done
tar -C $OUT -czf $OUT/diag32.tgz r && rm -rf $R
echo done
