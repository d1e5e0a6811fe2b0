#!/bin/sh
# signals_test.sh: what a farm expects of signals. SIGTERM, SIGINT and SIGHUP
# mid-render stop after the pass, write a valid image marked partial, leave
# no temporary file and exit 128 + the signal (143, 130, 129); a second
# signal ends the process at once, with no image. A reader that
# closes stdout (SIGPIPE) does not kill the render, and the failed write of
# the progress stream is reported.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
exr_attr="$CV_TEST_BUILDDIR/batch/exr_attr"
cp "$data/tiny.pbrt" "$data/long.yaml" "$data/jobs.yaml" "$tmp/"
cd "$tmp"

# start_long: starts the long job in the background (its pid in $pid) and
# waits (bounded) for its first finished pass.
start_long() {
    # The last run's events must be gone before this run starts: the
    # background job truncates run.jsonl only once it is scheduled, and a
    # grep that found the last run's progress would signal this one before
    # it has its handlers (a non-interactive shell starts background jobs
    # with SIGINT ignored, nohup with SIGHUP ignored: the signal is lost and
    # the job runs to the end).
    rm -rf out run.jsonl run.err
    "$CAVALRY_BATCH" --progress=json long.yaml >run.jsonl 2>run.err &
    pid=$!
    n=0
    while ! grep -q '"event":"progress"' run.jsonl 2>/dev/null; do
        n=$((n + 1))
        if [ "$n" -gt 600 ] || ! kill -0 "$pid" 2>/dev/null; then break; fi
        sleep 0.1
    done
}

# stop SIGNAL STATUS: starts the long job, sends SIGNAL after its first pass.
stop() {
    start_long
    kill -"$1" "$pid"
    set +e
    wait "$pid"
    rc=$?
    set -e
    check "SIG$1: exit status $2 (got $rc)" test "$rc" -eq "$2"
    check "SIG$1: image written" test -s out/long.exr
    check "SIG$1: marked partial" test "$("$exr_attr" out/long.exr cavalry.status 2>/dev/null)" = partial
    check "SIG$1: no temporary file" test -z "$(find out -name '.*.tmp' 2>/dev/null)"
    check "SIG$1: reported as partial" grep -q '"event":"job_partial"' run.jsonl
}
stop TERM 143
stop INT 130
stop HUP 129

# A second signal exits at once: no pass is finished, no image written,
# no further event. The process is stopped while both are sent, so that
# the second comes after the first has been handled, never merged with it
# while pending: two different signals, both pending at SIGCONT, are
# handled one after the other (only the main thread takes them).
start_long
kill -STOP "$pid"
kill -TERM "$pid"
kill -INT "$pid"
kill -CONT "$pid"
set +e
wait "$pid"
rc=$?
set -e
check "two signals: ended by one of them (status $rc)" test "$rc" -eq 143 -o "$rc" -eq 130
check "two signals: the first was taken" grep -q 'signal again to quit now' run.err
check "two signals: no image written" test ! -e out/long.exr
check "two signals: not reported partial" sh -c "! grep -q '\"event\":\"job_partial\"' run.jsonl"
check "two signals: no batch_finished" sh -c "! grep -q '\"event\":\"batch_finished\"' run.jsonl"

# A reader that has gone before the first event: every write of the
# progress stream meets a closed pipe.
rm -rf out
{ set +e; "$CAVALRY_BATCH" --progress=json jobs.yaml 2>pipe.err; echo $? >pipe.rc; } | true
check "closed stdout: the batch is not killed (status $(cat pipe.rc))" test "$(cat pipe.rc)" -eq 0
check "closed stdout: images written" test -s out/a.exr
check "closed stdout: the failed write is reported" grep -q 'progress stream: write failed' pipe.err
done_testing
