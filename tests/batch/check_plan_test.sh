#!/bin/sh
# check_plan_test.sh: --check makes every job's render plan, so what would
# only show while rendering shows before it: a scene's integrator that
# Cavalry substitutes (sppm, rendered with bdpt; issue 24, bug 9: a
# warning at the scene's file:line:col, an error under --strict) and an
# unknown colour name (an error at the manifest key). Nothing is rendered.
. "${srcdir:-.}/tests/setup.sh"
data="$CV_TEST_DATA/batch"
sed 's/^Integrator "path"/Integrator "sppm"/' "$data/tiny.pbrt" >"$tmp/sppm.pbrt"
line=$(grep -n '^Integrator' "$tmp/sppm.pbrt" | cut -d: -f1)
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

cat >"$tmp/sppm.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: sppm.pbrt
  - name: b
    scene: sppm.pbrt
    integrator: path
Y
run sppm --check
check "sppm --check: valid (exit $rc)" test "$rc" -eq 0
check "sppm --check: says where the scene asks for sppm" \
    grep -qF "sppm.pbrt:$line:1: integrator \"sppm\" is not supported: job \"a\" renders with \"bdpt\"" \
    "$tmp/sppm.err"
check "sppm --check: not about the job that names its integrator" \
    sh -c "! grep -q 'job \"b\"' '$tmp/sppm.err'"
run sppm --check --strict
check "sppm --check --strict: invalid (exit $rc)" test "$rc" -eq 3
check "sppm --check --strict: an error at the scene's Integrator" \
    grep -qF "sppm.pbrt:$line:1: integrator \"sppm\" is not supported (--strict)" "$tmp/sppm.err"
run sppm --strict
check "sppm --strict: nothing rendered (exit $rc)" test "$rc" -eq 3 -a ! -e "$tmp/a.exr"

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
