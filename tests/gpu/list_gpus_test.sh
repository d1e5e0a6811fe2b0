#!/bin/sh
# list_gpus_test.sh: --list-gpus lists at least one device and marks the
# chosen one; a bad --gpu or --backend is a usage error.
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
set +e
"$CAVALRY_BATCH" --gpu=99 /dev/null 2>"$tmp/err"; rc=$?
set -e
check "--gpu=99 fails" test "$rc" -ne 0
done_testing
