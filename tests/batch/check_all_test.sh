#!/bin/sh
# check_all_test.sh: issue 25 section 1. Every problem that would fail a job
# after it rendered is found by --check (and before the first job of a run),
# reported at manifest.yaml:LINE:COL: colour configs that are not OCIO
# configs, unresolvable ocio:// URIs, a missing $OCIO, a DWAA/DWAB EXR the
# library cannot write, a film over the renderer's pixel limit, an output
# folder that cannot be made, one file written by two jobs under different
# spellings, an output over one of the job's own inputs, job names "." and "..".
. "${srcdir:-.}/tests/setup.sh"
data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$tmp/"

# run NAME ARGS...: cavalry-batch --check ARGS on $tmp/NAME.yaml (20 s at
# most: /dev/zero must not be read forever); sets rc
run() {
    name=$1
    shift
    set +e
    (cd "$tmp" && timeout 20 "$CAVALRY_BATCH" --progress=none --check "$@" "$name.yaml") \
        >"$tmp/$name.out" 2>"$tmp/$name.err"
    rc=$?
    set -e
}
# bad NAME WHERE TEXT: NAME.yaml fails --check (exit 3) with TEXT at WHERE
bad() {
    run "$1"
    check "$1: --check fails (exit $rc)" test "$rc" -eq 3
    check "$1: at $1.yaml:$2" grep -qF "$1.yaml:$2: $3" "$tmp/$1.err"
}

for cfg in /etc/passwd /dev/zero ocio://no-such-builtin-config; do
    n=$(echo "$cfg" | tr -c 'a-z\n' _)
    cat >"$tmp/$n.yaml" <<Y
version: 1
jobs:
  - name: a
    scene: tiny.pbrt
    formats: [png]
    color:
      config: $cfg
Y
    bad "$n" 7:15 'job "a"'
done

cat >"$tmp/env.yaml" <<'Y'
version: 1
jobs:
  - name: a
    scene: tiny.pbrt
    formats: [png]
Y
set +e
(cd "$tmp" && OCIO="$tmp/missing.ocio" timeout 20 "$CAVALRY_BATCH" --check env.yaml) \
    >"$tmp/env.out" 2>"$tmp/env.err"
rc=$?
set -e
check "\$OCIO missing: --check fails (exit $rc)" test "$rc" -eq 3
check "\$OCIO missing: at the job" grep -qF 'env.yaml:3:5: job "a"' "$tmp/env.err"

# DWAA and DWAB: an error at the key exactly when this OpenEXR cannot
# write them (cavalry-manifest(5) names both)
for c in dwaa dwab; do
cat >"$tmp/$c.yaml" <<Y
version: 1
jobs:
  - name: a
    scene: tiny.pbrt
    exr: {compression: $c}
Y
run $c
if [ "$("$CAVALRY_BATCH" --version 2>&1 | grep -c 'OpenEXR 3\.[01]\b')" -gt 0 ] ||
   pkg-config --max-version=3.1.99 OpenEXR 2>/dev/null; then
    check "$c: --check fails with OpenEXR < 3.2 (exit $rc)" test "$rc" -eq 3
    check "$c: at the key" grep -qF "$c.yaml:5:24: job \"a\": EXR compression \"$c\"" \
        "$tmp/$c.err"
else
    check "$c: --check passes with OpenEXR >= 3.2 (exit $rc)" test "$rc" -eq 0
fi
done

# the renderer's real limit: 2^24 rendered pixels (cavalry-manifest(5))
cat >"$tmp/film.yaml" <<'Y'
version: 1
jobs:
  - name: uhd
    scene: tiny.pbrt
    resolution: [7680, 4320]
  - name: square
    scene: tiny.pbrt
    resolution: [4096, 4096]
Y
bad film 5:17 'job "uhd": a film of 7680x4320 rendered pixels is too large'
check "film: 4096x4096 is within the limit" sh -c "! grep -q 'job \"square\": a film' '$tmp/film.err'"
check "film: the man page says the limit" grep -q '4096' "${srcdir:-.}/man/cavalry-manifest.5"

# output folders that cannot be made
echo x >"$tmp/afile"
cat >"$tmp/outdir.yaml" <<'Y'
version: 1
defaults: {scene: tiny.pbrt}
jobs:
  - name: a
    output: afile/sub/{name}
  - name: b
    output: /proc/self/cavalry-no-such/{name}
  - name: c
    output: ok/{name}
Y
bad outdir 5:13 'job "a": output folder'
check "outdir: /proc at its key" grep -qF 'outdir.yaml:7:13: job "b": output folder' "$tmp/outdir.err"
check "outdir: a folder that can be made is fine" sh -c "! grep -q 'job \"c\"' '$tmp/outdir.err'"
check "outdir: --check makes no folder" test ! -e "$tmp/ok"

# one file, five spellings
cat >"$tmp/same.yaml" <<Y
version: 1
defaults: {scene: tiny.pbrt}
jobs:
  - name: a
    output: out/a
  - name: b
    output: ./out/a
  - name: c
    output: out//a
  - name: d
    output: out/../out/a
  - name: e
    output: $tmp/out/a
Y
bad same 7:13 'job "b": output'
for j in c:9 d:11 e:13; do
    check "same: job ${j%:*} too" grep -qF "same.yaml:${j#*:}:13: job \"${j%:*}\": output" "$tmp/same.err"
done

# outputs over the job's own inputs: the scene, an Include, a PLY, a texture
# (files named as outputs would be: NAME.exr, NAME.png)
mkdir -p "$tmp/in"
sed '/^WorldBegin/a Include "inc.exr"' "$data/tiny.pbrt" >"$tmp/in/main.exr"
echo 'Texture "t" "spectrum" "imagemap" "string filename" "tex.png"' >"$tmp/in/inc.exr"
echo 'Shape "plymesh" "string filename" "mesh.exr"' >>"$tmp/in/inc.exr"
printf 'version: 1\njobs:\n  - name: a\n    scene: tiny.pbrt\n    formats: [png]\n    output: in/tex\n' \
    >"$tmp/seed.yaml"
(cd "$tmp" && "$CAVALRY_BATCH" --progress=none seed.yaml >/dev/null 2>&1)
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' \
    >"$tmp/in/mesh.exr"
cat >"$tmp/over.yaml" <<'Y'
version: 1
defaults: {scene: in/main.exr}
jobs:
  - name: scene
    output: in/main
    formats: [exr]
  - name: include
    output: in/inc
    formats: [exr]
  - name: texture
    output: ./in/tex
    formats: [png]
  - name: ply
    output: in//mesh
    formats: [exr]
Y
bad over 5:13 'job "scene": output'
check "over: the Include" grep -qF 'over.yaml:8:13: job "include": output' "$tmp/over.err"
check "over: the texture" grep -qF 'over.yaml:11:13: job "texture": output' "$tmp/over.err"
check "over: the PLY" grep -qF 'over.yaml:14:13: job "ply": output' "$tmp/over.err"

for n in . ..; do
    printf 'version: 1\njobs:\n  - name: "%s"\n    scene: tiny.pbrt\n' "$n" >"$tmp/dot.yaml"
    bad dot 3:11 'name'
done
done_testing
