#!/bin/bash
# diag42.sh: where widening's time goes at 4 M and 16 M triangles (a debug build printing each step's time after glFinish)
cd "$(dirname "$0")"
export LC_ALL=C
R=$OUT/r; mkdir -p $R
(cd dbg && CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache_dbg tests/bvh/bvh_bench 4000000 --reps 3 > $R/dbg4.txt 2>&1; CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache_dbg tests/bvh/bvh_bench 16000000 --reps 3 > $R/dbg16.txt 2>&1)
grep -E "DBG|^  (widen|total)" $R/dbg4.txt | tail -6; grep -E "DBG|^  (widen|total)" $R/dbg16.txt | tail -6
tar -C $OUT -czf $OUT/diag42.tgz r && rm -rf $R
