#!/bin/bash
# diag13.sh: pass parameters written through a staging buffer (new) or straight into the uniform buffer (old)
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 16 --repeat 1 >/dev/null 2>&1
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
for round in 1 2; do
  for v in old new; do
    [ $v = old ] && B=bench/cavalry_bench_old || B=bench/cavalry_bench
    $B --bench $SC/veach-bidir/scene-v4.pbrt --spp 1024 --repeat 3 --json > $OUT/vb_${v}_$round.jsonl 2>/dev/null
    echo "veach-bidir $v r$round: $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $OUT/vb_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
    $B --bench $SC/cornell-box/scene-v4.pbrt --spp 1024 --repeat 3 --json > $OUT/cb_${v}_$round.jsonl 2>/dev/null
    echo "cornell $v r$round: $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $OUT/cb_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
    $B --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --json > $OUT/g4_${v}_$round.jsonl 2>/dev/null
    echo "g4 $v r$round: $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $OUT/g4_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  done
done
cat > /tmp/m.yaml <<YAML
version: 1
jobs:
  - name: vb
    scene: $SC/veach-bidir/scene-v4.pbrt
    output: /tmp/mo/{name}
    formats: [exr]
    spp: 64
YAML
src/cavalry-batch -v --force /tmp/m.yaml > /tmp/v.log 2>&1
echo "host-memory moves: $(grep 'HOST memory' /tmp/v.log | grep -o 'Buffer object [a-z -]*' | sort | uniq -c | tr -s ' ' | tr '\n' ';')"
