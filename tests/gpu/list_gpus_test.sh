#!/bin/sh
# list_gpus_test.sh: --list-gpus lists at least one device and marks the
# chosen one; a bad --backend is a usage error, and a --gpu index that no
# device has exits 4 before anything renders.
. "${srcdir:-.}/tests/setup.sh"
if ! "$CAVALRY_BATCH" --list-gpus >"$tmp/list" 2>"$tmp/err"; then
    skip_all "no GPU context: $(cat "$tmp/err")"
fi
check "lists a device with its OpenGL version" grep -q "OpenGL [0-9]" "$tmp/list"
check "marks exactly one device as chosen" test "$(grep -c '^\*' "$tmp/list")" -eq 1
set +e
"$CAVALRY_BATCH" --backend=vulkan --list-gpus 2>"$tmp/err"; rc=$?
set -e
check "unknown backend is a usage error (exit 2)" test "$rc" -eq 2
check "and says which backends exist" grep -q "auto, egl, osmesa" "$tmp/err"
# a GPU index that does not exist: exit 4, "no usable GPU context"
# (cavalry-batch(1), EXIT STATUS), on a manifest that is valid
cp "$CV_TEST_DATA/batch/tiny.pbrt" "$CV_TEST_DATA/batch/jobs.yaml" "$tmp/"
set +e
(cd "$tmp" && "$CAVALRY_BATCH" --gpu=99 --progress=none jobs.yaml) 2>"$tmp/err"; rc=$?
set -e
check "--gpu=99: exit 4 (got $rc)" test "$rc" -eq 4
check "--gpu=99: says which index" grep -q "no GPU with index 99" "$tmp/err"
check "--gpu=99: nothing written" test ! -e "$tmp/out"
done_testing
