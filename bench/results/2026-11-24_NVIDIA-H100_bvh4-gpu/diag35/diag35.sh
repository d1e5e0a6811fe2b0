#!/bin/bash
# diag35.sh: why the GPU-built 4-wide tree traces slower than the experiment: stack size (s64), the experiment's traverse.glsl (exp96/exp64), breadth-first node order (bfs binary)
cd "$(dirname "$0")"
export LC_ALL=C
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
new/bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
# run VARIANT_DATA_DIR BINARY_DIR cmd...
run() { local d=$1 b=$2; shift 2; (cd $b && CAVALRY_DATA_DIR=$d CAVALRY_CACHE_DIR=/tmp/cvcache_$(basename $d) "$@"); }
P=$PWD
for round in 1 2; do
  for v in base new vars/s64 vars/exp96 vars/exp64 bfs; do
    case $v in base|new|bfs) d=$P/$v; b=$P/$v;; *) d=$P/$v; b=$P/new;; esac
    n=$(basename $v)
    run $d $b env CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 2 --pass-spp 4 --json > $R/g4s_${n}_$round.jsonl 2>$R/g4s_${n}_$round.err
    echo "r$round $n g4s first $(g render.traversal.first_bounce_rays_per_s $R/g4s_${n}_$round.jsonl)| sec $(g render.traversal.secondary_only_rays_per_s $R/g4s_${n}_$round.jsonl)| shadow $(g render.traversal.shadow_rays_per_s $R/g4s_${n}_$round.jsonl)"
    if [ $round = 1 ]; then run $d $b tests/bvh/bvh_bench 4000000 --reps 1 --rays 4000000 > $R/bvhb4_$n.txt 2>&1; echo "   $(grep -E 'Mrays/s|nodes visited' $R/bvhb4_$n.txt | tr -s ' ' | tr '\n' ';')"; fi
  done
done
tar -C $OUT -czf $OUT/diag35.tgz r && rm -rf $R
echo done
