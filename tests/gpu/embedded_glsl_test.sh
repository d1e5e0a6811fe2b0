#!/bin/sh
# embedded_glsl_test.sh: the GLSL compiled into cavalry-batch is complete.
# Every other test points CAVALRY_DATA_DIR at the source tree, so a shader
# file missing from GLSL_FILES would pass them all and fail only in an
# installed or copied binary: check the list against glsl/ (less the
# probes under */test/, which only tests load), then render with the
# embedded files alone, through both integrators.
. "${srcdir:-.}/tests/setup.sh"
src=${CAVALRY_DATA_DIR:?}
embedded="${CV_TEST_BUILDDIR:?}/../src/gpu/glsl_embedded.c"
missing=""
for f in $(cd "$src/glsl" && find . -type f \( -name '*.comp' -o -name '*.glsl' -o -name '*.h' \) ! -path '*/test/*' | sed 's|^\./||' | sort); do
    grep -q "^    {\"$f\",\$" "$embedded" || missing="$missing $f"
done
check "every file under glsl/ is embedded (missing:${missing:- none})" test -z "$missing"

if ! "$CAVALRY_BATCH" --list-gpus >/dev/null 2>"$tmp/err"; then
    done_testing
    exit
fi
cp "$src/tests/data/batch/tiny.pbrt" "$tmp/"
cat >"$tmp/m.yaml" <<'YAML'
version: 1
defaults:
  scene: tiny.pbrt
  output: out/{name}
  formats: [exr]
  spp: 2
jobs:
  - name: path
  - name: rlpath
    integrator: rlpath
YAML
cd "$tmp"
check "renders with the embedded GLSL only" env -u CAVALRY_DATA_DIR "$CAVALRY_BATCH" -q m.yaml
check "both images written" test -s out/path.exr -a -s out/rlpath.exr
done_testing
