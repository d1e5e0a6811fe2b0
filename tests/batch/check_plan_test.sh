#!/bin/sh
# check_plan_test.sh: --check makes every job's render plan, so what would
# only show while rendering shows before it: a scene's integrator that
# Cavalry substitutes (issue 24, bug 9: a warning at the scene's
# file:line:col, an error under --strict) and an unknown colour name (an
# error at the manifest key). Nothing is rendered.
. "${srcdir:-.}/tests/setup.sh"
data="$CV_TEST_DATA/batch"
sed 's/^Integrator "path"/Integrator "bdpt"/' "$data/tiny.pbrt" >"$tmp/bdpt.pbrt"
line=$(grep -n '^Integrator' "$tmp/bdpt.pbrt" | cut -d: -f1)
cp "$data/tiny.pbrt" "$tmp/"

# run NAME ARGS...: runs cavalry-batch ARGS on $tmp/NAME.yaml; sets rc
run() {
    name=$1
    shift
    set +e
    "$CAVALRY_BATCH" --progress=none "$@" "$tmp/$name.yaml" >"$tmp/$name.out" 2>"$tmp/$name.err"
    rc=$?
    set -e
}

cat >"$tmp/bdpt.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: bdpt.pbrt
  - name: b
    scene: bdpt.pbrt
    integrator: path
Y
run bdpt --check
check "bdpt --check: valid (exit $rc)" test "$rc" -eq 0
check "bdpt --check: says where the scene asks for bdpt" \
    grep -qF "bdpt.pbrt:$line:1: integrator \"bdpt\" is not supported: job \"a\" renders with \"path\"" \
    "$tmp/bdpt.err"
check "bdpt --check: not about the job that names its integrator" \
    sh -c "! grep -q 'job \"b\"' '$tmp/bdpt.err'"
run bdpt --check --strict
check "bdpt --check --strict: invalid (exit $rc)" test "$rc" -eq 3
check "bdpt --check --strict: an error at the scene's Integrator" \
    grep -qF "bdpt.pbrt:$line:1: integrator \"bdpt\" is not supported (--strict)" "$tmp/bdpt.err"
run bdpt --strict
check "bdpt --strict: nothing rendered (exit $rc)" test "$rc" -eq 3 -a ! -e "$tmp/a.exr"

cat >"$tmp/view.yaml" <<'Y'
version: 1
defaults: {scene: tiny.pbrt, formats: [exr, png]}
jobs:
  - name: a
    color:
      view: Not A View
  - name: b
Y
run view --check
check "unknown view --check: invalid (exit $rc)" test "$rc" -eq 3
check "unknown view --check: at the key" grep -qF "view.yaml:6:13: job \"a\": unknown view \"Not A View\"" \
    "$tmp/view.err"
run view
check "unknown view: nothing rendered (exit $rc)" test "$rc" -eq 3 -a ! -e "$tmp/b.exr"
done_testing
