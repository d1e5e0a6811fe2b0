#!/bin/bash
# diag2.sh: shared scenes warm (bvh_bench --scene) and after idling; generated 0.5/1/4/16 M; cavalry_bench's builds
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR= CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv,noheader
mkdir -p $OUT/warm $OUT/idle $OUT/gen
for s in cornell-box veach-bidir veach-mis caustic-glass killeroos; do
  f=$SC/$s/scene-v4.pbrt
  [ $s = killeroos ] && f=$SC/$s/killeroo-coated-gold.pbrt
  [ $s = caustic-glass ] && f=$SC/$s/caustic-glass-v4.pbrt
  tests/bvh/bvh_bench --scene $f --reps 9 --check > $OUT/warm/$s.txt 2>&1
  echo "warm $s: $(grep -E 'check|^  (total|split_emit|treelet) ' $OUT/warm/$s.txt | tr -s ' ' | tr '\n' ' ')"
done
for s in veach-bidir killeroos; do
  f=$SC/$s/scene-v4.pbrt; [ $s = killeroos ] && f=$SC/$s/killeroo-coated-gold.pbrt
  tests/bvh/bvh_bench --scene $f --reps 3 --idle 2 --all > $OUT/idle/$s.txt 2>&1
  echo "idle $s: $(grep -E 'rep |^  total ' $OUT/idle/$s.txt | tr -s ' ' | tr '\n' ' ')"
done
for n in 500000 1000000 4000000 16000000; do
  tests/bvh/bvh_bench $n --reps 5 > $OUT/gen/$n.txt 2>&1
  echo "gen $n: $(grep -E '^  (total|split_emit|treelet) |SAH' $OUT/gen/$n.txt | tr -s ' '| tr '\n' ' ')"
done
SCENES="veach-bidir killeroos" ./shared_bvh.sh
for s in veach-bidir killeroos; do echo "cavalry_bench $s: $(grep -o '"bvh\.\(build_gpu_ms\|phase\.split_ms\|phase\.treelet_ms\)": [0-9.]*' $OUT/$s.jsonl | tr '\n' ' ')"; done
