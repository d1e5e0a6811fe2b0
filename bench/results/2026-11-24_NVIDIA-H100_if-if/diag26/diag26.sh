#!/bin/bash
# diag26.sh: any-hit loop form A/B (glsl copies in vars/): base 0d168c3, il1 (both loops interleaved), ilc (closest only)
cd "$(dirname "$0")"
export CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
for round in 1 2; do
for v in base il1 ilc; do
  export CAVALRY_DATA_DIR=$PWD/vars/$v
  bench/cavalry_bench --bench $SC/cornell-box/scene-v4.pbrt --spp 1024 --repeat 3 --json > $R/cornell_${v}_$round.jsonl 2>$R/cornell_${v}_$round.err
  bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 1024 --repeat 2 --json > $R/veach_${v}_$round.jsonl 2>$R/veach_${v}_$round.err
  bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --json > $R/g4_${v}_$round.jsonl 2>$R/g4_${v}_$round.err
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $SC/cornell-box/scene-v4.pbrt --spp 256 --repeat 2 --json > $R/cornells_${v}_$round.jsonl 2>$R/cornells_${v}_$round.err
  echo "$v r$round cornell $(g render.time_to_spp_gpu_ms $R/cornell_${v}_$round.jsonl) | veach $(g render.time_to_spp_gpu_ms $R/veach_${v}_$round.jsonl) | g4 $(g render.time_to_spp_gpu_ms $R/g4_${v}_$round.jsonl)"
  echo "$v r$round cornell-256 stages: intersect $(g render.stage.intersect_ms $R/cornells_${v}_$round.jsonl) shadow $(g render.stage.shadow_ms $R/cornells_${v}_$round.jsonl)"
done
done
tar -C $OUT -czf $OUT/diag26.tgz r && rm -rf $R
echo done
