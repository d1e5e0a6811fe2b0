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
# --array=1-9:2: task ids 1, 3, 5, 7, 9, as Slurm sets them.
: >slurm.txt
for t in 1 3 5 7 9; do
    SLURM_ARRAY_TASK_ID=$t SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=9 SLURM_ARRAY_TASK_STEP=2 \
        SLURM_ARRAY_TASK_COUNT=5 "$CAVALRY_BATCH" --dry-run many.yaml | cut -d: -f1 >>slurm.txt || true
done
sort slurm.txt >slurm.sorted
check "Slurm --array=1-9:2 covers every job once" cmp -s all.txt slurm.sorted
SLURM_ARRAY_TASK_ID=9 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=9 SLURM_ARRAY_TASK_STEP=2 \
    SLURM_ARRAY_TASK_COUNT=5 "$CAVALRY_BATCH" --dry-run many.yaml | cut -d: -f1 >last.txt || true
"$CAVALRY_BATCH" --dry-run --shard-index=4 --shard-count=5 many.yaml | cut -d: -f1 >shard4.txt
check "Slurm task 9 of 1-9:2 is shard 4 of 5" cmp -s last.txt shard4.txt
set +e
"$CAVALRY_BATCH" --dry-run --shard-count=3 many.yaml >nodex.out 2>nodex.err
rc=$?
set -e
check "--shard-count without an index: usage error (status $rc)" test "$rc" -eq 2
check "--shard-count without an index: says so" grep -q 'needs --shard-index' nodex.err
done_testing
