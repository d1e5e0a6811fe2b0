#!/bin/bash
# diag1.sh: warm BVH builds of the shared scenes (bvh_bench --scene), killeroos variants
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR= CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv,noheader
for s in cornell-box veach-bidir veach-mis caustic-glass killeroos; do
  f=$SC/$s/scene-v4.pbrt; [ -f $f ] || f=$(ls $SC/$s/*.pbrt | head -1)
  [ $s = killeroos ] && f=$SC/$s/killeroo-coated-gold.pbrt
  [ $s = caustic-glass ] && f=$SC/$s/caustic-glass-v4.pbrt
  tests/bvh/bvh_bench --scene $f --reps 9 --check --all > $OUT/$s.txt 2>&1
  echo "$s: $(grep -E 'total|check' $OUT/$s.txt | tr -s ' ' | tr '\n' ' ')"
done
f=$SC/killeroos/killeroo-coated-gold.pbrt
for v in "--rounds 0" "--rounds 1" "--split 0" "--split 0 --rounds 0"; do
  tests/bvh/bvh_bench --scene $f --reps 9 $v > "$OUT/killeroos $v.txt" 2>&1
  echo "killeroos $v: $(grep -E ' total|treelet |split ' "$OUT/killeroos $v.txt" | tr -s ' ' | tr '\n' ' ')"
done
for n in 500000 1000000; do tests/bvh/bvh_bench $n --reps 5 --check > $OUT/gen$n.txt 2>&1; echo "gen $n: $(grep -E ' total|check' $OUT/gen$n.txt | tr -s ' '| tr '\n' ' ')"; done
