#!/bin/bash
# diag43.sh: widening with the slot arrays kept in registers (constant-index loops, widen.glsl): bvh_test, build times at 4 M and 16 M; new (one atomic per node) and agg (one per group) against base (88fdad7)
cd "$(dirname "$0")"
export LC_ALL=C
R=$OUT/r; mkdir -p $R
P=$PWD
run() { local d=$1 b=$2; shift 2; (cd $b && CAVALRY_DATA_DIR=$d CAVALRY_CACHE_DIR=/tmp/cvcache_$(basename $d) "$@"); }
run $P/new $P/new tests/bvh/bvh_test > $R/bvh_test_new.txt 2>&1
echo "bvh_test new: $(grep -c '^ok' $R/bvh_test_new.txt) ok, $(grep -c '^not ok' $R/bvh_test_new.txt) not ok"
for v in base new vars/agg; do
  case $v in vars/*) b=$P/new;; *) b=$P/$v;; esac
  n=$(basename $v)
  run $P/$v $b tests/bvh/bvh_bench 4000000 --reps 9 > $R/bvhb4_$n.txt 2>&1
  echo "$n 4M: $(grep -E '^  (total|widen|wall) ' $R/bvhb4_$n.txt | tr -s ' ' | tr '\n' ';')"
  run $P/$v $b tests/bvh/bvh_bench 16000000 --reps 5 > $R/bvhb16_$n.txt 2>&1
  echo "$n 16M: $(grep -E '^  (total|widen|wall) ' $R/bvhb16_$n.txt | tr -s ' ' | tr '\n' ';')"
done
tar -C $OUT -czf $OUT/diag43.tgz r && rm -rf $R
echo done
