# tests/setup.sh: sourced by every shell test. Strict mode, C locale, a temp
# folder removed on exit unless the test failed, and TAP helpers.
set -eu
LC_ALL=C
export LC_ALL
: "${CAVALRY_BATCH:?run through make check}"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cavalry-test.XXXXXX")
tap_n=0
tap_failed=0
cleanup() {
    if [ "$tap_failed" -eq 0 ]; then rm -rf "$tmp"; else echo "# kept $tmp"; fi
}
trap cleanup EXIT
ok() { tap_n=$((tap_n + 1)); echo "ok $tap_n - $*"; }
not_ok() { tap_n=$((tap_n + 1)); tap_failed=$((tap_failed + 1)); echo "not ok $tap_n - $*"; }
# check DESCRIPTION COMMAND...: ok when the command succeeds.
check() { d=$1; shift; if "$@"; then ok "$d"; else not_ok "$d"; fi; }
# check_out DESCRIPTION FILE COMMAND...: the same, the command's output in FILE.
check_out() { d=$1; f=$2; shift 2; if "$@" >"$f"; then ok "$d"; else not_ok "$d"; fi; }
done_testing() { echo "1..$tap_n"; [ "$tap_failed" -eq 0 ]; }
skip_all() { echo "1..0 # SKIP $*"; trap - EXIT; rm -rf "$tmp"; exit 0; }
