#!/bin/sh
# man_examples_test.sh: the example manifests of cavalry-manifest(5) and
# cavalry-batch(1) pass --check, so that an example can never name a key,
# colour name or setting that does not exist (issue 25: the manifest page's
# example named a look the shipped config lacks). Each literal block that
# starts with "version:" is a manifest; its scenes are stood in for by a
# tiny scene. The --check commands of cavalry-batch(1)'s EXAMPLES run on
# the first of them.
. "${srcdir:-.}/tests/setup.sh"
man="${srcdir:-.}/man"
n=0
for page in "$man/cavalry-manifest.5" "$man/cavalry-batch.1"; do
    # one file per literal block (.Bd -literal ... .Ed), roff escapes undone
    awk -v dir="$tmp" -v base="$(basename "$page")" '
        /^\.Bd -literal/ { inb = 1; k++; f = dir "/" base "." k ".block"; next }
        /^\.Ed/ { inb = 0; close(f); next }
        inb { gsub(/\\-/, "-"); gsub(/\\&/, ""); gsub(/\\e/, "\\"); print > f }
    ' "$page"
done
for block in "$tmp"/*.block; do
    [ -e "$block" ] || continue
    head -n1 "$block" | grep -q '^version:' || continue
    n=$((n + 1))
    dir="$tmp/ex$n"
    mkdir -p "$dir"
    cp "$block" "$dir/shots.yaml"
    sed -n 's/^ *scene: *//p' "$block" | while read -r scene; do
        mkdir -p "$dir/$(dirname "$scene")"
        cp "$CV_TEST_DATA/batch/tiny.pbrt" "$dir/$scene"
    done
    name=$(basename "$block" .block)
    set +e
    (cd "$dir" && "$CAVALRY_BATCH" --check shots.yaml) >"$tmp/$n.out" 2>"$tmp/$n.err"
    rc=$?
    set -e
    check "$name: --check passes (exit $rc)" test "$rc" -eq 0
    [ "$rc" -eq 0 ] || sed 's/^/# /' "$tmp/$n.err"
done
check "the pages hold example manifests ($n)" test "$n" -ge 1
# cavalry-batch(1)'s --check examples, on the first example manifest
grep -h '^cavalry-batch --check' "$man/cavalry-batch.1" >"$tmp/cmds"
while read -r cmd; do
    set +e
    (cd "$tmp/ex1" && eval "\"\$CAVALRY_BATCH\" ${cmd#cavalry-batch }") >"$tmp/cmd.out" 2>&1
    rc=$?
    set -e
    check "cavalry-batch(1): \"$cmd\" (exit $rc)" test "$rc" -eq 0
done <"$tmp/cmds"
done_testing
