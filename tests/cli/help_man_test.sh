#!/bin/sh
# help_man_test.sh: every option and environment variable --help lists is
# documented in cavalry-batch(1), and the man pages are clean under
# mandoc -Tlint.
. "${srcdir:-.}/tests/setup.sh"
man1="$CAVALRY_DATA_DIR/man/cavalry-batch.1"
"$CAVALRY_BATCH" --help >"$tmp/help"
opts=$(grep -o -- '--[a-z][a-z-]*' "$tmp/help" | sort -u)
check "--help lists options" test -n "$opts"
for o in $opts; do
    # mdoc writes --foo as "Fl \-foo"
    name=${o#--}
    check "man page documents $o" grep -q -- "Fl \\\\-$name\\>" "$man1"
done
vars=$(grep -o -- '\<[A-Z][A-Z_]*[A-Z]\>' "$tmp/help" | grep '_\|^OCIO$' | sort -u)
check "--help lists environment variables" test -n "$vars"
for v in $vars; do
    check "man page documents $v" grep -q -- "Ev $v\\>" "$man1"
done
if command -v mandoc >/dev/null 2>&1; then
    for page in "$CAVALRY_DATA_DIR"/man/*.[15]; do
        check "mandoc -Tlint $(basename "$page")" sh -c "mandoc -Tlint -W warning '$page' >'$tmp/lint' 2>&1; test ! -s '$tmp/lint'"
    done
fi
"$CAVALRY_BATCH" --version >"$tmp/version"
check "--version prints the version" grep -q '^cavalry-batch [0-9]' "$tmp/version"
set +e
"$CAVALRY_BATCH" --no-such-option >/dev/null 2>"$tmp/e1"; rc=$?
"$CAVALRY_BATCH" >/dev/null 2>"$tmp/e2"; rc2=$?
"$CAVALRY_BATCH" --shard-index=3 --shard-count=2 x.yaml >/dev/null 2>"$tmp/e3"; rc3=$?
JOB_COMPLETION_INDEX=1 "$CAVALRY_BATCH" x.yaml >/dev/null 2>&1; rc4=$?
set -e
check "unknown option: exit 2" test "$rc" -eq 2
check "no manifest: exit 2" test "$rc2" -eq 2
check "shard index beyond count: exit 2" test "$rc3" -eq 2
check "JOB_COMPLETION_INDEX without --shard-count: exit 2" test "$rc4" -eq 2
# one prefix for every diagnostic, the log's, getopt's own messages included
check "unknown option: error: prefix" grep -qx 'error: unknown option --no-such-option' "$tmp/e1"
check "no manifest: error: prefix" grep -qx 'error: no manifest given' "$tmp/e2"
check "shard beyond count: error: prefix" grep -qx 'error: shard index 3 is not below shard count 2' "$tmp/e3"
check "no cavalry-batch: prefix" sh -c "! grep -q '^cavalry' '$tmp/e1' '$tmp/e2' '$tmp/e3'"
done_testing
