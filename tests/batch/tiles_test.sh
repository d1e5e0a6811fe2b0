#!/bin/sh
# tiles_test.sh: crops, tiles and header metadata (issue 28). A crop render
# is an EXR whose data window sits in the full display window and whose
# pixels, every channel, equal the same pixels of the full render at the
# same seed (samples are keyed by the full-film pixel); 2x2 tiles merged by
# --merge equal the full render bit for bit, and --merge refuses tiles that
# overlap, leave a gap or differ in display window, channels, pixel types or
# compression (exit status 3, nothing written); a tile that is not complete
# makes the merged image partial. OpenEXR's worldToCamera and worldToNDC map a
# known world point where the manifest's LookAt puts it; capDate, host,
# version, colour and spp are in the EXR header and the PNG text, which has
# one Software chunk. AOVs with formats [png] alone fail at their line.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
probe="$CV_TEST_BUILDDIR/batch/exr_probe"
cp "$data/tiny.pbrt" "$data/tiles.pbrt" "$data/tiles.yaml" "$tmp/"
cd "$tmp"

check_out "--dry-run" plan.txt "$CAVALRY_BATCH" --dry-run tiles.yaml
check "--dry-run shows the crop as WxH+X+Y of the film" grep -q "^crop: .* 16x12 crop 8x6+4+6, 3 spp" plan.txt
check "--dry-run shows no crop for the whole film" grep -q "^full: .* 16x12, 3 spp" plan.txt
check "renders" "$CAVALRY_BATCH" --progress=none tiles.yaml
check_out "full: display = data window" w_full.txt "$probe" windows out/full.exr
check "full window is 16x12" grep -qx "display 0 0 15 11 data 0 0 15 11" w_full.txt
check_out "crop windows" w_crop.txt "$probe" windows out/crop.exr
check "crop [0.25, 0.75, 0.5, 1]: data window 4..11 x 6..11 in the full display window" \
    grep -qx "display 0 0 15 11 data 4 6 11 11" w_crop.txt
check "crop equals the full render's pixels, every channel" "$probe" inside out/full.exr out/crop.exr
for t in t00 t10 t01 t11; do
    check "tile $t equals the full render's pixels" "$probe" inside out/full.exr "out/$t.exr"
done
check "--merge" "$CAVALRY_BATCH" --merge merged.exr out/t00.exr out/t10.exr out/t01.exr out/t11.exr
check_out "merged windows" w_merged.txt "$probe" windows merged.exr
check "merged image is the full display window" cmp w_full.txt w_merged.txt
check "merged tiles equal the unsplit render bit for bit" "$probe" inside out/full.exr merged.exr
check "and the other way round" "$probe" inside merged.exr out/full.exr
check "merged keeps the tiles' metadata" sh -c "test \"\$('$probe' attr merged.exr cavalry.seed)\" = 11"
check "merged has no tile's settings hash" sh -c "! '$probe' attr merged.exr cavalry.settingsHash 2>/dev/null"
check "a render with another seed is not the same pixels" sh -c "! '$probe' inside out/other_seed.exr out/t00.exr 2>/dev/null"
check "--merge refuses an overlap" sh -c "! '$CAVALRY_BATCH' --merge bad.exr out/t00.exr out/t10.exr out/t01.exr out/t11.exr out/crop.exr 2>overlap.err"
check "overlap named" grep -q "overlap" overlap.err
check "--merge refuses a gap" sh -c "! '$CAVALRY_BATCH' --merge bad.exr out/t00.exr out/t10.exr out/t01.exr 2>gap.err"
check "gap named" grep -q "cover 144 of the display window's 192 pixels" gap.err
check "no output after a refused merge" test ! -e bad.exr
check "the merged tiles are complete" \
    sh -c "test \"\$('$probe' attr merged.exr cavalry.status)\" = complete"

# Tiles that do not match t00, t01 and t11: each in place of t10, each
# refused with exit status 3 and nothing written. A tile stopped by its
# time limit merges, and the merged image says partial.
cat >odd.yaml <<'Y'
version: 1
defaults:
  scene: tiles.pbrt
  output: odd/{name}
  formats: [exr]
  spp: 3
  seed: 11
  aovs: [albedo, normal, depth]
  crop: [0.5, 1, 0, 0.5]
jobs:
  - name: channels
    aovs: []
  - name: float
    exr: {half: false}
  - name: piz
    exr: {compression: piz}
  - name: window
    resolution: [32, 24]
  - name: cut
    crop: [0.5, 1, 0.5, 1]
    spp: 16777216
    time_limit: 0.001
Y
check "renders odd tiles" "$CAVALRY_BATCH" --progress=none odd.yaml
check "the cut tile is not complete" \
    sh -c "test \"\$('$probe' attr odd/cut.exr cavalry.status)\" = time-limit"
# refused TILE WANT: t00 TILE t01 t11 do not merge; exit 3, WANT said
refused() {
    rm -f bad.exr
    "$CAVALRY_BATCH" --merge bad.exr out/t00.exr "odd/$1.exr" out/t01.exr out/t11.exr \
        2>odd.err && rc=0 || rc=$?
    if [ "$rc" -eq 3 ] && grep -q "odd/$1.exr: $2" odd.err && test ! -e bad.exr; then
        ok "--merge refuses a tile of other $1: exit 3, said, nothing written"
    else
        not_ok "--merge refuses a tile of other $1 (exit $rc)"; sed 's/^/# /' odd.err
    fi
}
refused channels "channels differ from the first tile's"
refused float "channels differ from the first tile's"
refused piz "compression differs from the first tile's"
refused window "display window differs from out/t00.exr's"
"$CAVALRY_BATCH" --merge bad.exr out/t00.exr out/t10.exr out/t01.exr out/t11.exr out/crop.exr \
    2>/dev/null && rc=0 || rc=$?
check "an overlap: exit 3 (got $rc)" test "$rc" -eq 3
"$CAVALRY_BATCH" --merge bad.exr out/t00.exr out/t10.exr out/t01.exr 2>/dev/null && rc=0 || rc=$?
check "a gap: exit 3 (got $rc)" test "$rc" -eq 3
check "a partial tile merges" "$CAVALRY_BATCH" --merge part.exr out/t00.exr out/t10.exr \
    out/t01.exr odd/cut.exr
check "a partial tile: the merged image is partial" \
    sh -c "test \"\$('$probe' attr part.exr cavalry.status)\" = partial"

# worldToCamera: eye (2,0,0) looking at the origin, up +y: camera +z is
# world -x, camera +x (right) is world +z, so (0, 0.25, 0.5) is at
# (0.5, 0.25, 2) in camera space (OpenEXR's, pbrt's: +z forward).
check_out "worldToCamera" p_cam.txt "$probe" point out/look.exr worldToCamera 0 0.25 0.5
check "worldToCamera maps the point" grep -qx "0.5000 0.2500 2.0000" p_cam.txt
# worldToNDC: 45 degrees on the 12-pixel axis, screen [-4/3, 4/3] x [-1, 1]:
# x = (0.5 / (2 tan 22.5) + 4/3) / (8/3), y = (1 - 0.25 / (2 tan 22.5)) / 2.
check_out "worldToNDC" p_ndc.txt "$probe" point out/look.exr worldToNDC 0 0.25 0.5
check "worldToNDC maps the point (y down)" grep -q "^0.7263 0.3491 " p_ndc.txt
check_out "worldToNDC centre" p_mid.txt "$probe" point out/look.exr worldToNDC 0 0 0
check "the look-at point is the image centre" grep -q "^0.5000 0.5000 " p_mid.txt
check "capDate in OpenEXR's form" sh -c "'$probe' attr out/look.exr capDate | grep -Eqx '[0-9]{4}:[0-9]{2}:[0-9]{2} [0-9]{2}:[0-9]{2}:[0-9]{2}'"
check "utcOffset" sh -c "'$probe' attr out/look.exr utcOffset >/dev/null"
check "host" sh -c "test -n \"\$('$probe' attr out/look.exr cavalry.host)\""
check "version" sh -c "'$probe' attr out/look.exr cavalry.version | grep -q ."
check "target spp" sh -c "test \"\$('$probe' attr out/look.exr cavalry.sppTarget)\" = 3"
check "reached spp" sh -c "test \"\$('$probe' attr out/look.exr cavalry.spp)\" = 3"
check "OCIO view" sh -c "'$probe' attr out/look.exr cavalry.ocioView | grep -q ."
check "PNG: one Software chunk" sh -c "test \"\$('$probe' pngtext out/look.png Software | wc -l)\" -eq 1"
check "PNG: Software names cavalry-batch" sh -c "'$probe' pngtext out/look.png Software | grep -q '^cavalry-batch '"
check "PNG: no lowercase software chunk" sh -c "test -z \"\$('$probe' pngtext out/look.png software)\""
check "PNG: worldToCamera text" sh -c "test \"\$('$probe' pngtext out/look.png worldToCamera | wc -w)\" -eq 16"
check "PNG: capDate, OCIO config, target spp" sh -c "'$probe' pngtext out/look.png capDate | grep -q . && '$probe' pngtext out/look.png cavalry.ocioConfig | grep -q . && '$probe' pngtext out/look.png cavalry.sppTarget | grep -qx 3"

cat >aovpng.yaml <<'Y'
version: 1
jobs:
  - name: p
    scene: tiny.pbrt
    formats: [png]
    aovs: [albedo]
Y
check "AOVs with formats [png] alone fail" sh -c "! '$CAVALRY_BATCH' --check aovpng.yaml 2>aovpng.err"
check "at the aovs key's line:col" grep -q "aovpng.yaml:6:11: job \"p\": aovs need the exr format" aovpng.err
cat >badcrop.yaml <<'Y'
version: 1
jobs:
  - name: p
    scene: tiny.pbrt
    crop: [0.5, 0.5, 0, 1]
Y
check "an empty crop fails" sh -c "! '$CAVALRY_BATCH' --check badcrop.yaml 2>badcrop.err"
check "at its line:col" grep -q "badcrop.yaml:5:11: crop: empty window" badcrop.err
done_testing
