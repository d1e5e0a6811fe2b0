#!/bin/bash
# diag11.sh: renderer counters read straight from the queue buffer (CV_COUNTERS_DIRECT=1, as before) or through a copy
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
mkdir -p /tmp/m && cat > /tmp/m/m.yaml <<YAML
version: 1
jobs:
  - name: vb
    scene: $SC/veach-bidir/scene-v4.pbrt
    output: /tmp/m/out/{name}
    formats: [exr]
    spp: 64
YAML
for v in direct copy; do
  [ $v = direct ] && e=CV_COUNTERS_DIRECT=1 || e=CV_NOTHING=1
  env $e src/cavalry-batch -v --force /tmp/m/m.yaml > /tmp/m/$v.log 2>&1
  echo "$v: $(grep -c 'HOST memory' /tmp/m/$v.log) host-memory moves: $(grep 'HOST memory' /tmp/m/$v.log | grep -o 'Buffer object [a-z ]*' | sort | uniq -c | tr -s ' ' | tr '\n' ';')"
done
bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 16 --repeat 1 >/dev/null 2>&1
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
for round in 1 2; do
  for v in direct copy; do
    [ $v = direct ] && e=CV_COUNTERS_DIRECT=1 || e=CV_NOTHING=1
    env $e bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 1024 --repeat 3 --json > $OUT/vb_${v}_$round.jsonl 2>/dev/null
    echo "veach-bidir $v r$round: $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $OUT/vb_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
    env $e bench/cavalry_bench --bench $SC/cornell-box/scene-v4.pbrt --spp 1024 --repeat 3 --json > $OUT/cb_${v}_$round.jsonl 2>/dev/null
    echo "cornell $v r$round: $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $OUT/cb_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
    env $e bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --json > $OUT/g4_${v}_$round.jsonl 2>/dev/null
    echo "g4 $v r$round: $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*\|"render.secondary_rays_per_s": [0-9.e+]*' $OUT/g4_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  done
done
