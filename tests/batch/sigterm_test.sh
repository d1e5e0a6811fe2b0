#!/bin/sh
# sigterm_test.sh: SIGTERM mid-render stops after the pass, writes a valid
# image marked partial, leaves no temporary file, and exits 130.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
exr_attr="$CV_TEST_BUILDDIR/batch/exr_attr"
cp "$data/tiny.pbrt" "$data/long.yaml" "$tmp/"
cd "$tmp"
"$CAVALRY_BATCH" --progress=json long.yaml >run.jsonl 2>run.err &
pid=$!
# Wait (bounded) for the first finished pass.
n=0
while ! grep -q '"event":"progress"' run.jsonl 2>/dev/null; do
    n=$((n + 1))
    if [ "$n" -gt 600 ] || ! kill -0 "$pid" 2>/dev/null; then break; fi
    sleep 0.1
done
kill -TERM "$pid"
set +e
wait "$pid"
rc=$?
set -e
check "exit status 130 (got $rc)" test "$rc" -eq 130
check "image written" test -s out/long.exr
check "marked partial" test "$("$exr_attr" out/long.exr cavalry.status)" = partial
check "no temporary file" test -z "$(find out -name '.*.tmp')"
check "reported as partial" grep -q '"event":"job_partial"' run.jsonl
done_testing
