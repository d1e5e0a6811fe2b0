#!/bin/sh
# png_tag_test.sh: each job's PNG carries the colour tags of its display
# encoding (output/png_write.h): cICP 1/13 and an sRGB chunk for sRGB,
# cICP 12/13 for Display P3, cICP 1/1 for Rec.1886, and no colour chunk for
# a Raw view; also with a config whose scene_linear is ACEScg.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
cp "$CV_TEST_DATA/batch/tiny.pbrt" "$tmp/"
cd "$tmp"
cat >jobs.yaml <<EOT
version: 1
defaults:
  scene: tiny.pbrt
  output: out/{name}
  formats: [png]
  resolution: [8, 6]
  spp: 1
jobs:
  - name: srgb
    color: {display: sRGB}
  - name: p3
    color: {display: Display P3}
  - name: rec1886
    color: {display: Rec.1886}
  - name: raw
    color: {display: sRGB, view: Raw}
  - name: acescg_p3
    color: {config: $CV_TEST_DATA/color/acescg.ocio, display: Display P3, view: Encoded}
EOT
check "renders" "$CAVALRY_BATCH" -q jobs.yaml

# The PNG's bytes as one line of hex pairs.
hex() { od -An -v -tx1 "$1" | tr -d '\n' | tr -s ' '; }
# has FILE BYTES / lacks FILE BYTES: whether the file holds BYTES (a chunk's
# length and type, so that text chunks naming "sRGB" do not count).
has() { hex "$1" | grep -q " $2"; }
lacks() { ! has "$@"; }
cicp="00 00 00 04 63 49 43 50"
srgb_chunk="00 00 00 01 73 52 47 42"
gama="00 00 00 04 67 41 4d 41"
chrm="00 00 00 20 63 48 52 4d"
check "sRGB: cICP 1/13/0/1" has out/srgb.png "$cicp 01 0d 00 01"
check "sRGB: sRGB chunk" has out/srgb.png "$srgb_chunk"
check "Display P3: cICP 12/13/0/1" has out/p3.png "$cicp 0c 0d 00 01"
check "Display P3: no sRGB chunk" lacks out/p3.png "$srgb_chunk"
check "Display P3: gAMA" has out/p3.png "$gama"
check "Display P3: cHRM" has out/p3.png "$chrm"
check "Rec.1886: cICP 1/1/0/1" has out/rec1886.png "$cicp 01 01 00 01"
check "Raw: no cICP" lacks out/raw.png "$cicp"
check "Raw: no sRGB chunk" lacks out/raw.png "$srgb_chunk"
check "Raw: no gAMA" lacks out/raw.png "$gama"
check "Raw: no cHRM" lacks out/raw.png "$chrm"
check "ACEScg config, P3 encoded view: cICP 12/13/0/1" has out/acescg_p3.png "$cicp 0c 0d 00 01"
done_testing
