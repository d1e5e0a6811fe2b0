#!/bin/sh
# mattes_bdpt_test.sh: bdpt's alpha, ID AOVs and Cryptomatte (issue 27) are
# the path integrator's: both take a camera ray's mattes at its first hit
# (glsl/trace/matte.glsl), and bdpt's camera subpaths start with the path
# integrator's camera rays, so on mattes.pbrt (two quads under a white
# environment, an orthographic camera: tests/batch/mattes_test.sh) every
# matte channel of the one equals the other's bit for bit.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
probe="$CV_TEST_BUILDDIR/batch/matte_probe"
cp "$data/mattes.pbrt" "$tmp/"
cd "$tmp"
cat >both.yaml <<'Y'
version: 1
defaults:
  scene: mattes.pbrt
  output: out/{name}
  spp: 16
  seed: 3
  formats: [exr]
  alpha: true
  aovs: [object_id, material_id, crypto_object, crypto_material]
  exr:
    half: false
jobs:
  - name: path
    integrator: path
  - name: bdpt
    integrator: bdpt
Y
check "path and bdpt render the mattes" "$CAVALRY_BATCH" --progress=none --strict both.yaml
crypto=""
for t in CryptoObject CryptoMaterial; do
    for l in 00 01 02; do
        for c in R G B A; do crypto="$crypto $t$l.$c"; done
    done
done
check "alpha: bdpt's is path's" "$probe" same out/path.exr out/bdpt.exr A
check "ID AOVs: bdpt's are path's" "$probe" same out/path.exr out/bdpt.exr object_id.id material_id.id
# shellcheck disable=SC2086
check "Cryptomatte: bdpt's is path's" "$probe" same out/path.exr out/bdpt.exr $crypto
check "the edge pixel is half covered (alpha is no constant)" sh -c \
    "'$probe' value out/bdpt.exr 0 2 A | awk '{ ok = \$1 > 0.3 && \$1 < 0.7 } END { exit !(NR == 1 && ok) }'"
v() { "$probe" value "$1" "$2" "$3" "$4"; }
check "bdpt: the environment seen directly adds nothing" test "$(v out/bdpt.exr 3 0 G)" = 0
check "bdpt: the environment lights the quads (as path: within 10 %)" sh -c \
    "awk -v a=\"\$('$probe' value out/bdpt.exr 2 2 R)\" -v b=\"\$('$probe' value out/path.exr 2 2 R)\" \
     'BEGIN { exit !(b > 0.3 && a > 0.9 * b && a < 1.1 * b) }'"
check "bdpt: Cryptomatte coverage sums to alpha" "$probe" sums out/bdpt.exr CryptoObject
done_testing
