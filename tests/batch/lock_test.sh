#!/bin/sh
# lock_test.sh: several workers on one manifest never render a job twice.
# A job whose lock another process holds is skipped, not rendered; two
# identical workers started together with --resume render each job of a
# small manifest exactly once between them, and every output is written.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
command -v flock >/dev/null 2>&1 || skip_all "no flock(1)"
data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$data/jobs.yaml" "$tmp/"
cd "$tmp"

# A lock held elsewhere (flock(1) keeps it while the batch runs; -o: the
# batch does not inherit its descriptor).
mkdir out
flock -o out/.a.lock "$CAVALRY_BATCH" --progress=json jobs.yaml >held.jsonl 2>held.err
check "a job whose lock is held is skipped" \
    grep -q '"event":"job_skipped",.*"job":"a".*another process is rendering it' held.jsonl
check "...and not written" test ! -e out/a.exr
check "the other jobs are rendered" test -s out/b.exr -a -s out/c.png
check "the lock file is hidden beside the output" test -e out/.b.lock

# Two identical workers on eight jobs, started together.
rm -rf out
{
    echo 'version: 1'
    echo 'defaults: {scene: tiny.pbrt, output: "out/{name}", formats: [exr], spp: 16}'
    echo 'jobs:'
    for j in 1 2 3 4 5 6 7 8; do echo "  - name: j$j"; done
} >eight.yaml
"$CAVALRY_BATCH" --resume --progress=json eight.yaml >w1.jsonl 2>w1.err &
p1=$!
"$CAVALRY_BATCH" --resume --progress=json eight.yaml >w2.jsonl 2>w2.err &
p2=$!
set +e
wait "$p1"; r1=$?
wait "$p2"; r2=$?
set -e
check "both workers succeed ($r1, $r2)" test "$r1" -eq 0 -a "$r2" -eq 0
cat w1.jsonl w2.jsonl | grep '"event":"job_finished"' | sed 's/.*"job":"\([^"]*\)".*/\1/' | sort >rendered.txt
printf 'j%s\n' 1 2 3 4 5 6 7 8 >all.txt
check "each job rendered exactly once ($(tr '\n' ' ' <rendered.txt))" cmp -s rendered.txt all.txt
n=0
for j in 1 2 3 4 5 6 7 8; do [ -s "out/j$j.exr" ] && n=$((n + 1)); done
check "all eight outputs written ($n)" test "$n" -eq 8
done_testing
