#!/bin/sh
# manifest_errors_test.sh: an invalid manifest or scene stops the batch
# before anything renders: exit 3, a file:line:col message, no output.
. "${srcdir:-.}/tests/setup.sh"
data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$data/broken.pbrt" "$tmp/"

# expect_invalid NAME WANTED-MESSAGE: runs $tmp/NAME.yaml
expect_invalid() {
    set +e
    "$CAVALRY_BATCH" --progress=none "$tmp/$1.yaml" >"$tmp/$1.out" 2>"$tmp/$1.err"
    rc=$?
    set -e
    check "$1: exit status 3 (got $rc)" test "$rc" -eq 3
    check "$1: says \"$2\"" grep -qF -- "$2" "$tmp/$1.err"
    check "$1: nothing written" test ! -e "$tmp/out"
}

cat >"$tmp/unknown_key.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: tiny.pbrt
    sp: 4
Y
expect_invalid unknown_key "unknown_key.yaml:5:5: unknown key \"sp\""

cat >"$tmp/wrong_type.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: tiny.pbrt
    spp: lots
Y
expect_invalid wrong_type "wrong_type.yaml:5:10:"

cat >"$tmp/negative_spp.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: tiny.pbrt
    spp: -4
Y
expect_invalid negative_spp "negative_spp.yaml:5:10:"

cat >"$tmp/missing_scene.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: nowhere.pbrt
Y
expect_invalid missing_scene "missing_scene.yaml:4:12:"

cat >"$tmp/duplicate.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: tiny.pbrt
  - name: a
    scene: tiny.pbrt
Y
expect_invalid duplicate "duplicate.yaml:5:11:"

printf 'version: 1\njobs:\n  - name: [a\n' >"$tmp/syntax.yaml"
expect_invalid syntax "syntax.yaml:"

cat >"$tmp/bad_scene.yaml" <<'Y'
version: 1
defaults:
  output: out/{name}
jobs:
  - name: ok
    scene: tiny.pbrt
  - name: bad
    scene: broken.pbrt
Y
expect_invalid bad_scene "broken.pbrt:4:1"
check "bad_scene: the job is named" grep -qF 'bad_scene.yaml:7:5: job "bad"' "$tmp/bad_scene.err"
done_testing
