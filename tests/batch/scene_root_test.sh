#!/bin/sh
# scene_root_test.sh: --scene-root (cavalry-batch(1)) holds when rendering,
# with --check and with --dry-run, not only for --dump-scene: a scene whose
# real path and every file it reads lie under the root renders (named
# through "sub/.." too); an Include that leaves the root, a scene file that
# is a symbolic link out of it and an env.file outside it are refused at
# the place that names them, exit status 3, and nothing is rendered.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
cd "$tmp"
mkdir -p root/sub outside
echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.4 0.3 ]' >root/sub/mat.pbrt
cp root/sub/mat.pbrt outside/mat.pbrt
# the Include is line 9 of each
sed '/^WorldBegin/a Include "sub/mat.pbrt"' "$data/tiny.pbrt" >root/good.pbrt
sed '/^WorldBegin/a Include "../outside/mat.pbrt"' "$data/tiny.pbrt" >root/bad.pbrt
cp "$data/tiny.pbrt" outside/o.pbrt
ln -s ../outside/o.pbrt root/link.pbrt
sed 's|"string filename" "../trace/oracle/envmap.pfm"|"string filename" "sky.pfm"|' \
    "$data/env.pbrt" >root/env.pbrt
cp "$data/gray.pfm" root/sky.pfm
cp "$data/gray.pfm" outside/sky.pfm
cat >m.yaml <<'Y'
version: 1
defaults: {output: "out/{name}", spp: 1, formats: [exr]}
jobs:
  - name: good
    scene: root/sub/../good.pbrt
  - name: bad
    scene: root/bad.pbrt
  - name: link
    scene: root/link.pbrt
  - name: env
    scene: root/env.pbrt
    env: {file: outside/sky.pfm}
  - name: env_in
    scene: root/env.pbrt
    env: {file: root/sky.pfm}
Y

check "renders a scene under the root" \
    "$CAVALRY_BATCH" --progress=none --scene-root=root --only good m.yaml
check "its image" test -s out/good.exr
rm -rf out
for how in "--progress=none" "--check" "--dry-run"; do
    "$CAVALRY_BATCH" $how --scene-root=root --only good --only bad --only link m.yaml \
        >out.txt 2>err.txt && rc=0 || rc=$?
    check "$how: a scene reading outside the root: exit 3 (got $rc)" test "$rc" -eq 3
    check "$how: the Include refused at its file:line:col" grep -q \
        '^error: m.yaml:6:5: job "bad": root/bad.pbrt:9:1: cannot include "../outside/mat.pbrt": .*outside the scene root' \
        err.txt
    check "$how: the scene file linked from outside refused" \
        grep -q '^m.yaml:8:5: job "link": root/link.pbrt: outside the scene root' err.txt
done
check "nothing rendered" test ! -e out
"$CAVALRY_BATCH" --progress=none --scene-root=root --only env m.yaml 2>env.err && rc=0 || rc=$?
check "an env.file outside the root: exit 3 (got $rc)" test "$rc" -eq 3
check "the env.file refused at its key" \
    grep -q '^error: m.yaml:12:17: job "env": .*outside the scene root' env.err
check "nothing rendered" test ! -e out
check "an env.file under the root passes --check" \
    "$CAVALRY_BATCH" --check --scene-root=root --only env_in m.yaml
check "without --scene-root the outside files are read" \
    "$CAVALRY_BATCH" --progress=none --only bad --only link m.yaml
done_testing
