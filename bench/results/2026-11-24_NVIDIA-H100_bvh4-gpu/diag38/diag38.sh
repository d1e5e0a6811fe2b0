#!/bin/bash
# diag38.sh: which of the small differences from the experiment's traverse.glsl costs ~3 %: A new as is, B the bvec ands inline, C B + the experiment's pad, D the experiment's file
cd "$(dirname "$0")"
export LC_ALL=C
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
new/bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
P=$PWD
for round in 1 2; do
  for n in A B C D; do
    (cd new && CAVALRY_DATA_DIR=$P/vars/$n CAVALRY_CACHE_DIR=/tmp/cvcache_$n CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 2 --pass-spp 4 --json > $R/g4s_${n}_$round.jsonl 2>$R/g4s_${n}_$round.err)
    echo "r$round $n first $(g render.traversal.first_bounce_rays_per_s $R/g4s_${n}_$round.jsonl)| sec $(g render.traversal.secondary_only_rays_per_s $R/g4s_${n}_$round.jsonl)| shadow $(g render.traversal.shadow_rays_per_s $R/g4s_${n}_$round.jsonl)"
  done
done
tar -C $OUT -czf $OUT/diag38.tgz r && rm -rf $R
echo done
