#!/bin/bash
# diag33.sh: the 4-wide tree built on the GPU: bvh_test on the device, build times and random-ray traversal (bvh_bench), base (88fdad7) against new
cd "$(dirname "$0")"
export LC_ALL=C
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
run() { local v=$1; shift; (cd $v && CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache_$v "$@"); }
run new tests/bvh/bvh_test > $R/bvh_test_new.txt 2>&1
echo "bvh_test new: $(grep -c '^ok' $R/bvh_test_new.txt) ok, $(grep -c '^not ok' $R/bvh_test_new.txt) not ok"
run new tests/bvh/bvh_bench 4000000 --reps 1 --check > $R/bvhb4_check.txt 2>&1; grep -E "check:|nodes " $R/bvhb4_check.txt
for v in base new; do
  run $v tests/bvh/bvh_bench 4000000 --reps 9 --rays 4000000 > $R/bvhb4_$v.txt 2>&1
  echo "$v 4M: $(grep -E '^  (total|widen|collapse) ' $R/bvhb4_$v.txt | tr -s ' ' | tr '\n' ';') $(grep -E 'Mrays/s|nodes visited' $R/bvhb4_$v.txt | tr -s ' ' | tr '\n' ';')"
  run $v tests/bvh/bvh_bench 16000000 --reps 5 > $R/bvhb16_$v.txt 2>&1
  echo "$v 16M: $(grep -E '^  (total|widen|collapse|wall) ' $R/bvhb16_$v.txt | tr -s ' ' | tr '\n' ';') $(grep -E '^  nodes' $R/bvhb16_$v.txt)"
done
tar -C $OUT -czf $OUT/diag33.tgz r && rm -rf $R
echo done
