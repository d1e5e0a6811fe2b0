#!/bin/sh
# progress_test.sh: the machine progress streams, read with a real JSON
# parser (progress_check.py): --progress=json events carry ISO 8601 UTC
# times that never go back, the phases in order, percent and ETA, outputs as
# a list, the scene's time in its first job; an invalid manifest (a file or
# standard input) gives error events with file, line and column;
# batch_finished names the jobs --fail-fast never started; every event has
# the fields cavalry-batch(1) lists for it, of their types; --progress=openjd
# prints only OpenJD lines ending at 100; --progress=bar draws a live line
# per job (samples, rays per second, time left) on standard error and
# nothing on standard output; --progress=auto is the bar on a terminal and
# nothing off one.
. "${srcdir:-.}/tests/setup.sh"
py=/usr/bin/python3
[ -x "$py" ] || skip_all "no $py"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
checker="$CV_TEST_DATA/../batch/progress_check.py"
data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$data/jobs.yaml" "$tmp/"
cd "$tmp"
# A job's events name the GPU where the device has an index (not OSMesa).
fields=fields
"$CAVALRY_BATCH" --list-gpus | grep -q '^\* *[0-9]' && fields=fields_gpu

check_out "json: renders" run.jsonl "$CAVALRY_BATCH" --progress=json jobs.yaml 2>run.err
check "json: events, times, phases, outputs" "$py" "$checker" json run.jsonl done=3 \
    not_started= scene_seconds_once
check "json: every line has a time" test "$(grep -c '"time":"' run.jsonl)" -eq "$(wc -l <run.jsonl)"
check "json: each event's fields, of their types" "$py" "$checker" json run.jsonl $fields
check_out "json: --resume" resume.jsonl "$CAVALRY_BATCH" --progress=json --resume jobs.yaml \
    2>resume.err
check "json: skipped jobs' fields, detail saying why" "$py" "$checker" json resume.jsonl \
    $fields done=0
check "json: three jobs skipped" test "$(grep -c '"event":"job_skipped"' resume.jsonl)" -eq 3

printf 'version: 1\njobs:\n  - name: a\n    scene: missing.pbrt\n    spp: zero\n' >bad.yaml
"$CAVALRY_BATCH" --progress=json bad.yaml >bad.jsonl 2>bad.err && rc=0 || rc=$?
check "invalid manifest: exit 3 (got $rc)" test "$rc" -eq 3
check "invalid manifest: JSON error events" "$py" "$checker" json bad.jsonl errors file=bad.yaml
check "invalid manifest: one event per problem" test "$(grep -c '"event":"error"' bad.jsonl)" -eq 2
check "invalid manifest: line and column of spp" grep -q '"line":5,"column":10' bad.jsonl
check "invalid manifest: error events' fields" "$py" "$checker" json bad.jsonl errors fields

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
check "fail-fast: job_failed's fields" "$py" "$checker" json ff.jsonl $fields done=0

# The bar: on standard error, a line naming each job, then a line redrawn
# after each pass: "[###...] 4/4 spp  1.2 Mrays/s  0.1s  ETA 0s".
cr=$(printf '\r')
bar_line='^  \[[#.]{30}\] [0-9]+/4 spp  [0-9.]+ [kMG]rays/s  [0-9.]+s  ETA [0-9]+s'
check_out "bar: renders" bar.out "$CAVALRY_BATCH" --progress=bar jobs.yaml 2>bar.err
check "bar: nothing on standard output" test ! -s bar.out
check "bar: a line per job on standard error" sh -c \
    "grep -qx '\[1/3\] a' bar.err && grep -qx '\[2/3\] b' bar.err && grep -qx '\[3/3\] c' bar.err"
check "bar: samples, rays per second and time left" sh -c \
    "tr '\\r' '\\n' <bar.err | grep -Eq '$bar_line'"
check "bar: the line is redrawn in place" grep -q "$cr" bar.err
check "bar: each job's end" test "$(grep -c '^  done: [24] spp in ' bar.err)" -eq 3
# auto off a terminal (files here): no bar, nothing on standard output.
for how in "--progress=auto" ""; do
    check_out "auto ($how): renders" auto.out "$CAVALRY_BATCH" $how jobs.yaml 2>auto.err
    check "auto ($how) off a terminal: nothing on standard output" test ! -s auto.out
    check "auto ($how) off a terminal: no bar" sh -c \
        "! grep -Eq '^\[1/3\] a|\[[#.]{30}\]|ETA' auto.err && ! grep -q '$cr' auto.err"
done
# auto on a terminal, where script(1) gives one: the bar.
if command -v script >/dev/null 2>&1 && script -qec true /dev/null >/dev/null 2>&1; then
    script -qec "'$CAVALRY_BATCH' --progress=auto jobs.yaml" /dev/null >tty.out 2>&1 </dev/null || :
    check "auto on a terminal: the bar" sh -c \
        "grep -q '\[1/3\] a' tty.out && tr '\\r' '\\n' <tty.out | grep -Eq '$bar_line'"
else
    ok "auto on a terminal # SKIP no script(1)"
fi

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
sed 's/"rays_per_s":[0-9.]*,//' run.jsonl >norate.jsonl
check "checker: a missing field fails" sh -c "! '$py' '$checker' json norate.jsonl fields >/dev/null"
sed 's/"index":\([0-9]*\)/"index":"\1"/' run.jsonl >strindex.jsonl
check "checker: a field of another type fails" \
    sh -c "! '$py' '$checker' json strindex.jsonl fields >/dev/null"
done_testing
