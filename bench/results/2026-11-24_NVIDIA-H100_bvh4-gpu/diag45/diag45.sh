#!/bin/bash
# diag45.sh: after the review mends (cv_widen_inner tests the slot count itself): bvh_test and build times at 4 M and 16 M
cd "$(dirname "$0")"
export LC_ALL=C
R=$OUT/r; mkdir -p $R
run() { (cd new && CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache_new "$@"); }
run tests/bvh/bvh_test > $R/bvh_test_new.txt 2>&1
echo "bvh_test new: $(grep -c '^ok' $R/bvh_test_new.txt) ok, $(grep -c '^not ok' $R/bvh_test_new.txt) not ok"
run tests/bvh/bvh_bench 4000000 --reps 9 > $R/bvhb4_new.txt 2>&1
echo "new 4M: $(grep -E '^  (total|widen|wall) |nodes' $R/bvhb4_new.txt | tr -s ' ' | tr '\n' ';')"
run tests/bvh/bvh_bench 16000000 --reps 5 > $R/bvhb16_new.txt 2>&1
echo "new 16M: $(grep -E '^  (total|widen|wall) |nodes' $R/bvhb16_new.txt | tr -s ' ' | tr '\n' ';')"
tar -C $OUT -czf $OUT/diag45.tgz r && rm -rf $R
