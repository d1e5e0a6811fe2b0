#!/bin/bash
# stage2.sh SRC DEST: only what the A/B scripts run (no bench/results)
set -e
S=$1; D=$2
rm -rf $D; mkdir -p $D/bench $D/tests/bvh $D/src
cd $S
cp -r glsl configs $D/
cp bench/cavalry_bench bench/gen_scene $D/bench/
cp tests/bvh/bvh_test tests/bvh/bvh_bench $D/tests/bvh/
cp src/cavalry-batch $D/src/
du -sh $D
