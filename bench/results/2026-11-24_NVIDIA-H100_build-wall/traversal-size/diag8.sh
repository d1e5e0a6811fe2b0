#!/bin/bash
# diag8.sh: incoherent ray rate against tree size (bvh_bench --rays): does traversal fall off past a few hundred MB?
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR= LC_ALL=C
for n in 250000 500000 1000000 2000000 4000000 8000000 16000000; do
  tests/bvh/bvh_bench $n --reps 1 --rays 8000000 > $OUT/rays_$n.txt 2>&1
  echo "$n: $(grep -E 'bytes/tri|Mrays|nodes visited' $OUT/rays_$n.txt | tr -s ' ' | tr '\n' ' ')"
done
