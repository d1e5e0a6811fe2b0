#!/bin/sh
# progress_test.sh: the machine progress streams, read with a real JSON
# parser (progress_check.py): --progress=json events carry ISO 8601 UTC
# times that never go back, the phases in order, percent and ETA, outputs as
# a list, the scene's time in its first job; an invalid manifest (a file or
# standard input) gives error events with file, line and column;
# batch_finished names the jobs --fail-fast never started; --progress=openjd
# prints only OpenJD lines ending at 100.
. "${srcdir:-.}/tests/setup.sh"
py=/usr/bin/python3
[ -x "$py" ] || skip_all "no $py"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
checker="$CV_TEST_DATA/../batch/progress_check.py"
data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$data/jobs.yaml" "$tmp/"
cd "$tmp"

check_out "json: renders" run.jsonl "$CAVALRY_BATCH" --progress=json jobs.yaml 2>run.err
check "json: events, times, phases, outputs" "$py" "$checker" json run.jsonl done=3 \
    not_started= scene_seconds_once
check "json: every line has a time" test "$(grep -c '"time":"' run.jsonl)" -eq "$(wc -l <run.jsonl)"

printf 'version: 1\njobs:\n  - name: a\n    scene: missing.pbrt\n    spp: zero\n' >bad.yaml
"$CAVALRY_BATCH" --progress=json bad.yaml >bad.jsonl 2>bad.err && rc=0 || rc=$?
check "invalid manifest: exit 3 (got $rc)" test "$rc" -eq 3
check "invalid manifest: JSON error events" "$py" "$checker" json bad.jsonl errors file=bad.yaml
check "invalid manifest: one event per problem" test "$(grep -c '"event":"error"' bad.jsonl)" -eq 2
check "invalid manifest: line and column of spp" grep -q '"line":5,"column":10' bad.jsonl

"$CAVALRY_BATCH" --progress=json - <bad.yaml >stdin.jsonl 2>stdin.err && rc=0 || rc=$?
check "invalid manifest on stdin: exit 3 (got $rc)" test "$rc" -eq 3
check "invalid manifest on stdin: errors at <stdin>" "$py" "$checker" json stdin.jsonl errors \
    'file=<stdin>'
check "invalid manifest on stdin: log says <stdin>:line:col" grep -q '^<stdin>:5:10: spp' stdin.err

# The first job fails when it starts (its lock file is a folder, which the
# plan does not look at): with --fail-fast the others never start.
sed 's|output: out/{name}|output: ff/{name}|' jobs.yaml >ff.yaml
mkdir -p ff/.a.lock
"$CAVALRY_BATCH" --progress=json --fail-fast ff.yaml >ff.jsonl 2>ff.err && rc=0 || rc=$?
check "fail-fast: exit 1 (got $rc)" test "$rc" -eq 1
check "fail-fast: b and c never started" "$py" "$checker" json ff.jsonl done=0 not_started=b,c
check "fail-fast: job_failed with an error" grep -q '"event":"job_failed",.*"job":"a",.*"error":' ff.jsonl

check_out "openjd: renders" run.openjd "$CAVALRY_BATCH" --progress=openjd --force jobs.yaml 2>openjd.err
check "openjd: only openjd lines, progress rising to 100" "$py" "$checker" openjd run.openjd
check "openjd: status names the phases" grep -q '^openjd_status: a: render$' run.openjd
"$CAVALRY_BATCH" --progress=openjd bad.yaml >bad.openjd 2>/dev/null || :
check "openjd: an invalid manifest is openjd_fail" grep -q '^openjd_fail: bad.yaml:5:10: spp' bad.openjd

# The checker itself must catch what it checks: a time going back, a
# missing phase, a non-JSON line.
sed '3s/"time":"[^"]*"/"time":"2000-01-01T00:00:00.000Z"/' run.jsonl >back.jsonl
check "checker: a time going back fails" sh -c "! '$py' '$checker' json back.jsonl done=3 2>/dev/null >&2"
grep -v '"phase":"render"' run.jsonl >norender.jsonl
check "checker: a missing phase fails" sh -c "! '$py' '$checker' json norender.jsonl done=3 >/dev/null"
sed 's/"time":"\([^"]*\)Z"/"time":"\1"/' run.jsonl >nozone.jsonl
check "checker: a time without Z fails" sh -c "! '$py' '$checker' json nozone.jsonl done=3 >/dev/null"
done_testing
