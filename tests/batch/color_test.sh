#!/bin/sh
# color_test.sh: a job's color.exposure and color.look (cavalry-manifest(5))
# reach its PNG, and only its PNG. Exposure is in stops on scene-linear
# values before the view: +1 doubles them and -1 halves them before the
# sRGB curve (doubling after it would not match). A look is applied in
# place of the view's own looks; without one, the view's looks apply. Each
# PNG is compared with the job's own float EXR through the curve, within
# one 8-bit code value, in a test config whose views are plain sRGB, one
# with a look that halves.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
exr_scale="$CV_TEST_BUILDDIR/batch/exr_scale"
exr_same="$CV_TEST_BUILDDIR/batch/exr_same"
cp "$CV_TEST_DATA/batch/tiny.pbrt" "$tmp/"
cd "$tmp"
cat >test.ocio <<'O'
ocio_profile_version: 2
roles:
  scene_linear: lin_rec709
  default: lin_rec709
displays:
  sRGB:
    - !<View> {name: Plain, colorspace: srgb_display}
    - !<View> {name: Graded, colorspace: srgb_display, looks: half}
looks:
  - !<Look>
    name: half
    process_space: lin_rec709
    transform: !<MatrixTransform> {matrix: [0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1]}
  - !<Look>
    name: double
    process_space: lin_rec709
    transform: !<MatrixTransform> {matrix: [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]}
colorspaces:
  - !<ColorSpace>
    name: lin_rec709
    isdata: false
  - !<ColorSpace>
    name: srgb_display
    isdata: false
    from_scene_reference: !<ExponentWithLinearTransform> {gamma: [2.4, 2.4, 2.4, 1], offset: [0.055, 0.055, 0.055, 0], direction: inverse}
O
cat >jobs.yaml <<'Y'
version: 1
defaults:
  scene: tiny.pbrt
  output: out/{name}
  formats: [exr, png]
  resolution: [8, 6]
  spp: 2
  seed: 5
  exr: {half: false}
  png: {bits: 8}
  color: {config: test.ocio, display: sRGB, view: Plain}
jobs:
  - name: plain
  - name: up
    color: {exposure: 1}
  - name: down
    color: {exposure: -1}
  - name: graded
    color: {view: Graded}
  - name: looked
    color: {look: double}
  - name: replaced
    color: {view: Graded, look: double}
Y
check "renders" "$CAVALRY_BATCH" --progress=none jobs.yaml
for j in up down graded looked replaced; do
    check "$j: the EXR is the plain job's" "$exr_same" out/plain.exr "out/$j.exr"
done
check "no exposure, no look: the sRGB curve of the EXR" \
    "$exr_scale" display out/plain.exr out/plain.png 1
check "exposure +1: twice the linear values, then the curve" \
    "$exr_scale" display out/plain.exr out/up.png 2
check "exposure +1 changes the PNG" \
    sh -c "! '$exr_scale' display out/plain.exr out/up.png 1 2>/dev/null"
check "exposure -1: half the linear values" "$exr_scale" display out/plain.exr out/down.png 0.5
check "a view's own look applies without color.look" \
    "$exr_scale" display out/plain.exr out/graded.png 0.5
check "color.look applies" "$exr_scale" display out/plain.exr out/looked.png 2
check "color.look replaces the view's look" \
    "$exr_scale" display out/plain.exr out/replaced.png 2
done_testing
