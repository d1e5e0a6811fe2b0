#!/bin/sh
# workers_test.sh: a multi-GPU batch (--gpu all, --gpu 0,0, --workers N) as
# a farm sees it, on llvmpipe's one device with two workers: every job of a
# five-job manifest is rendered exactly once, into the images a single
# process renders (the same pixels, bit for bit); the parent's JSON stream
# parses, shows both workers and tags every job event with its worker and
# device; a failing job is reported once, with its error, and the exit
# status is the batch's; a job whose worker dies is reported failed once
# while the other worker renders the rest; SIGTERM stops every worker,
# leaves images marked partial and no temporary file, and exits 143;
# --resume and a manifest on standard input work; OpenJD progress rises to
# 100; jobs stopped by their time limit are no failure, a worker stopped by
# a signal of its own is; a worker whose GPU does not open leaves its jobs
# to the others (exit 4 when none opens); --gpu all on a machine with one
# device runs as a single process does.
. "${srcdir:-.}/tests/setup.sh"
py=/usr/bin/python3
[ -x "$py" ] || skip_all "no $py"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
checker="$CV_TEST_DATA/../batch/progress_check.py"
exr_same="$CV_TEST_BUILDDIR/batch/exr_same"
exr_attr="$CV_TEST_BUILDDIR/batch/exr_attr"
cp "$CV_TEST_DATA/batch/tiny.pbrt" "$tmp/"
cd "$tmp"
{
    echo 'version: 1'
    echo 'defaults: {scene: tiny.pbrt, output: "{name}", formats: [exr], spp: 4, seed: 11}'
    echo 'jobs:'
    for j in a b c d e; do echo "  - name: $j"; done
} >five.yaml
# names of the jobs with an event, sorted: "job_finished" FILE
# how many lines of FILE (which may not exist yet) match: count PATTERN FILE
count() { cat "$2" 2>/dev/null | grep -c "$1" || :; }
# wait_for PATTERN N FILE: until FILE has N lines with PATTERN, the batch
# ($pid) has ended, or two minutes have passed.
wait_for() {
    n=0
    while [ "$(count "$1" "$3")" -lt "$2" ]; do
        n=$((n + 1))
        if [ "$n" -gt 1200 ] || ! kill -0 "$pid" 2>/dev/null; then break; fi
        sleep 0.1
    done
}
jobs_with() { grep "\"event\":\"$1\"" "$2" | sed 's/.*"job":"\([^"]*\)".*/\1/' | sort | tr '\n' ' '; }

# The reference: one process.
"$CAVALRY_BATCH" --progress=none --output-dir=single five.yaml 2>single.err
check_out "two workers: exit 0" two.jsonl "$CAVALRY_BATCH" --workers=2 --progress=json \
    --output-dir=two five.yaml 2>two.err
check "two workers: each job rendered once ($(jobs_with job_finished two.jsonl))" \
    test "$(jobs_with job_finished two.jsonl)" = "a b c d e "
check "two workers: each job started once" test "$(jobs_with job_started two.jsonl)" = "a b c d e "
check "two workers: the stream parses, shows both workers, tags job events" \
    "$py" "$checker" json two.jsonl done=5 not_started= each_once workers=0,1
for j in a b c d e; do
    check "two workers: $j.exr has the single process's pixels" "$exr_same" single/$j.exr two/$j.exr
done
check "two workers: no temporary file" test -z "$(find two -name '.*.tmp')"
check "--gpu 0,0 is two workers too" sh -c "'$CAVALRY_BATCH' --gpu=0,0 --progress=json \
    --output-dir=list five.yaml 2>list.err >list.jsonl && '$py' '$checker' json list.jsonl \
    done=5 each_once workers=0,1"

# A manifest on standard input reaches every worker.
"$CAVALRY_BATCH" --workers=2 --progress=json --output-dir=stdin - <five.yaml >stdin.jsonl \
    2>stdin.err && rc=0 || rc=$?
check "manifest on stdin: exit 0 (got $rc)" test "$rc" -eq 0
check "manifest on stdin: each job once" "$py" "$checker" json stdin.jsonl done=5 each_once

# --resume: nothing to do, then only the job whose image is gone.
check_out "resume: exit 0" resume.jsonl "$CAVALRY_BATCH" --workers=2 --resume --progress=json \
    --output-dir=two five.yaml 2>resume.err
check "resume: every job skipped once" test "$(jobs_with job_skipped resume.jsonl)" = "a b c d e "
rm -f two/c.exr
check_out "resume after a loss: exit 0" resume2.jsonl "$CAVALRY_BATCH" --workers=2 --resume \
    --progress=json --output-dir=two five.yaml 2>resume2.err
check "resume after a loss: only c rendered" test "$(jobs_with job_finished resume2.jsonl)" = "c "
check "resume after a loss: c as before" "$exr_same" single/c.exr two/c.exr

# A job that fails (its lock file is a folder): reported once, the others
# rendered, exit 1.
mkdir -p fail/.c.lock
"$CAVALRY_BATCH" --workers=2 --progress=json --output-dir=fail five.yaml >fail.jsonl \
    2>fail.err && rc=0 || rc=$?
check "failing job: exit 1 (got $rc)" test "$rc" -eq 1
check "failing job: one job_failed, for c" test "$(jobs_with job_failed fail.jsonl)" = "c "
check "failing job: with its error" grep -q '"event":"job_failed",.*"error":".*lock' fail.jsonl
check "failing job: the error logged once" test "$(grep -c 'job \\"c\\"\|job "c"' fail.err)" -eq 1
check "failing job: the others rendered once" "$py" "$checker" json fail.jsonl done=4 each_once
"$CAVALRY_BATCH" --workers=2 --progress=openjd --output-dir=fail --force five.yaml \
    >fail.openjd 2>/dev/null || :
check "failing job: OpenJD lines, progress rising to 100" "$py" "$checker" openjd fail.openjd

# A worker that dies (SIGKILL) with a job in flight: the parent reports that
# job failed, once; the other jobs are rendered.
{
    echo 'version: 1'
    echo 'defaults: {scene: tiny.pbrt, output: "out/{name}", formats: [exr], spp: 4}'
    echo 'jobs:'
    echo '  - {name: long, spp: 16000000}'
    for j in b c d e; do echo "  - name: $j"; done
} >crash.yaml
"$CAVALRY_BATCH" --workers=2 --progress=json --output-dir=crash crash.yaml >crash.jsonl \
    2>crash.err &
pid=$!
# Once the four short jobs are done, only the worker on "long" is left.
wait_for '"event":"job_finished"' 4 crash.jsonl
for w in $(ps -o pid= --ppid "$pid"); do kill -KILL "$w" 2>/dev/null || :; done
set +e
wait "$pid"
rc=$?
set -e
check "dead worker: exit 1 (got $rc)" test "$rc" -eq 1
check "dead worker: its job failed once" test "$(jobs_with job_failed crash.jsonl)" = "long "
check "dead worker: says how it died" grep -q '"error":"job \\"long\\": worker [01] (gpu 0) was killed by signal 9' crash.jsonl
check "dead worker: every job ended once" "$py" "$checker" json crash.jsonl done=4 each_once

# SIGTERM to the parent stops both workers after their pass.
{
    echo 'version: 1'
    echo 'defaults: {scene: tiny.pbrt, output: "out/{name}", formats: [exr], spp: 16000000}'
    echo 'jobs:'
    for j in l0 l1 l2; do echo "  - name: $j"; done
} >long.yaml
"$CAVALRY_BATCH" --workers=2 --progress=json long.yaml >term.jsonl 2>term.err &
pid=$!
wait_for '"event":"progress"' 2 term.jsonl
workers=$(ps -o pid= --ppid "$pid" | tr '\n' ' ')
kill -TERM "$pid" || :
set +e
wait "$pid"
rc=$?
set -e
check "SIGTERM: exit 143 (got $rc)" test "$rc" -eq 143
left=0
for w in $workers; do kill -0 "$w" 2>/dev/null && left=$((left + 1)); done
check "SIGTERM: no worker left running ($workers)" test "$left" -eq 0
check "SIGTERM: no temporary file" test -z "$(find out -name '.*.tmp' 2>/dev/null)"
partial=$(jobs_with job_partial term.jsonl)
check "SIGTERM: jobs in flight reported partial ($partial)" test -n "$partial"
for j in $partial; do
    check "SIGTERM: $j.exr marked partial" \
        test "$("$exr_attr" "out/$j.exr" cavalry.status 2>/dev/null)" = partial
done
check "SIGTERM: the stream ends with batch_finished" "$py" "$checker" json term.jsonl each_once

# A time limit that stops both workers' jobs is no failure, as in one process.
"$CAVALRY_BATCH" --workers=2 --time-limit=1 --progress=json --output-dir=limit long.yaml \
    >limit.jsonl 2>limit.err && rc=0 || rc=$?
check "time limit: exit 0 (got $rc)" test "$rc" -eq 0
check "time limit: every job partial, once" test "$(jobs_with job_partial limit.jsonl)" = "l0 l1 l2 "

# SIGTERM to one worker alone: its job is partial, the other worker goes on
# (to its time limit), and the batch is not done: exit 1.
"$CAVALRY_BATCH" --workers=2 --time-limit=3 --progress=json --output-dir=one long.yaml \
    >one.jsonl 2>one.err &
pid=$!
wait_for '"event":"progress"' 2 one.jsonl
w=$(ps -o pid= --ppid "$pid" | head -n 1)
kill -TERM $w || :
set +e
wait "$pid"
rc=$?
set -e
check "SIGTERM to one worker: exit 1 (got $rc)" test "$rc" -eq 1
check "SIGTERM to one worker: every job ended once" "$py" "$checker" json one.jsonl \
    each_once not_started=

# A worker whose GPU does not open: the other renders every job; only when
# none opens is the status 4.
"$CAVALRY_BATCH" --gpu=0,999 --progress=json --output-dir=nogpu five.yaml >nogpu.jsonl \
    2>nogpu.err && rc=0 || rc=$?
check "one GPU missing: exit 0 (got $rc)" test "$rc" -eq 0
check "one GPU missing: the other worker renders all" "$py" "$checker" json nogpu.jsonl \
    done=5 each_once
check "one GPU missing: said once" test "$(grep -c 'no GPU with index 999' nogpu.err)" -eq 1
"$CAVALRY_BATCH" --gpu=998,999 --progress=json --output-dir=nogpu2 five.yaml >nogpu2.jsonl \
    2>nogpu2.err && rc=0 || rc=$?
check "no GPU opens: exit 4 (got $rc)" test "$rc" -eq 4
check "no GPU opens: every job not started" "$py" "$checker" json nogpu2.jsonl done=0 \
    not_started=a,b,c,d,e

# Usage errors.
"$CAVALRY_BATCH" --workers=0 five.yaml >/dev/null 2>w0.err && rc=0 || rc=$?
check "--workers=0: exit 2 (got $rc)" test "$rc" -eq 2
"$CAVALRY_BATCH" --gpu=0, five.yaml >/dev/null 2>g.err && rc=0 || rc=$?
check "--gpu=0,: exit 2 (got $rc)" test "$rc" -eq 2

# --gpu all with one device: one process, as without it.
if [ "$("$CAVALRY_BATCH" --list-gpus 2>/dev/null | grep -c '^[* ] [0-9]')" -eq 1 ]; then
    check_out "--gpu all, one device: exit 0" all.jsonl "$CAVALRY_BATCH" --gpu=all \
        --progress=json --output-dir=all five.yaml 2>all.err
    check "--gpu all, one device: a single process's events" "$py" "$checker" json all.jsonl \
        done=5 each_once no_workers
    check "--gpu all, one device: same pixels" "$exr_same" single/e.exr all/e.exr
else
    ok "# SKIP --gpu all with one device: this machine lists several"
fi
done_testing
