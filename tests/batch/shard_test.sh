#!/bin/sh
# shard_test.sh: shards partition the jobs exactly, for several counts, from
# options and from Slurm's environment.
. "${srcdir:-.}/tests/setup.sh"
data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$data/many.yaml" "$tmp/"
cd "$tmp"
"$CAVALRY_BATCH" --dry-run many.yaml | cut -d: -f1 | sort >all.txt
check "dry run lists 11 jobs" test "$(wc -l <all.txt)" -eq 11
for n in 1 2 3 4 7; do
    : >union.txt
    i=0
    while [ "$i" -lt "$n" ]; do
        "$CAVALRY_BATCH" --dry-run --shard-index=$i --shard-count=$n many.yaml | cut -d: -f1 >>union.txt
        i=$((i + 1))
    done
    sort union.txt >union.sorted
    check "$n shards cover every job exactly once" cmp -s all.txt union.sorted
done
: >slurm.txt
for t in 1 2 3; do
    SLURM_ARRAY_TASK_ID=$t SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=3 \
        "$CAVALRY_BATCH" --dry-run many.yaml | cut -d: -f1 >>slurm.txt
done
sort slurm.txt >slurm.sorted
check "Slurm array of 3 (ids 1..3) covers every job once" cmp -s all.txt slurm.sorted
done_testing
