#!/bin/sh
# mattes_test.sh: alpha, ID AOVs and Cryptomatte (issue 28) on two quads
# side by side under a white environment (tests/data/batch/mattes.pbrt).
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
probe="$CV_TEST_BUILDDIR/batch/matte_probe"
cp "$data/mattes.pbrt" "$data/mattes.yaml" "$tmp/"
cd "$tmp"
check "renders" "$CAVALRY_BATCH" --progress=none mattes.yaml
v() { "$probe" value "$1" "$2" "$3" "$4"; }
# within FILE X Y CHANNEL LO HI: LO <= value <= HI
within() {
    x=$("$probe" value "$1" "$2" "$3" "$4") || return 1
    awk -v x="$x" -v lo="$5" -v hi="$6" 'BEGIN { exit !(x != "" && x + 0 >= lo && x + 0 <= hi) }'
}
# one line of numbers, and the awk condition holds for it
holds() { awk "$1"' { n++ } END { exit !(n == 1 && ok) }' "$2"; }

# alpha: coverage; the environment seen directly is transparent
check "background alpha 0" test "$(v out/m.exr 3 0 A)" = 0
check "background colour 0 (premultiplied)" test "$(v out/m.exr 3 0 G)" = 0
check "covered alpha 1" test "$(v out/m.exr 2 2 A)" = 1
check "the environment still lights the quads" within out/m.exr 2 2 R 0.3 1
check "half-covered outer pixel: alpha about 0.5" within out/m.exr 0 2 A 0.35 0.65
check "its colour is premultiplied: below the covered pixel's" \
    awk -v e="$(v out/m.exr 0 2 B)" -v c="$(v out/m.exr 1 2 B)" 'BEGIN { exit !(c > 0 && e != "" && e < 0.8 * c) }'
check "without alpha: A is 1 on the background" test "$(v out/opaque.exr 3 0 A)" = 1
check "without alpha: the environment is seen" within out/opaque.exr 3 0 G 0.99 1.01
same() { a=$(v "$1" "$3" "$4" "$5") && b=$(v "$2" "$3" "$4" "$5") && test -n "$a" -a "$a" = "$b"; }
check "alpha leaves the covered pixels' colour as it is" same out/m.exr out/opaque.exr 2 2 R

# PNG: RGBA, straight colour
check_out "png pixels" bg.txt "$probe" png out/m.png 3 0
check "png background alpha 0" grep -q " 0\$" bg.txt
check_out "png covered" in.txt "$probe" png out/m.png 1 2
check "png covered alpha 255" grep -q " 255\$" in.txt
check_out "png edge" edge.txt "$probe" png out/m.png 0 2
check "png edge alpha about half" holds '{ ok = $4 > 90 && $4 < 165 }' edge.txt
check "png edge colour straight: as the covered pixel's" \
    holds "{ ok = \$3 >= $(cut -d' ' -f3 in.txt) - 3 && \$3 <= $(cut -d' ' -f3 in.txt) + 3 }" edge.txt
check "without alpha the png stays RGB" sh -c "'$probe' png out/opaque.png 0 0 2>&1 | grep -q 'not 8-bit RGBA'"

# ID AOVs: 1 + index of sample 0's first hit; names in the header
check "object_id: 0 on the background" test "$(v out/m.exr 3 0 object_id.id)" = 0
check "object_id: the instance is object 1" test "$(v out/m.exr 1 2 object_id.id)" = 1
check "object_id: the shape is object 2" test "$(v out/m.exr 6 2 object_id.id)" = 2
check "material_id differs between the quads" \
    test "$(v out/m.exr 6 2 material_id.id)" != "$(v out/m.exr 1 2 material_id.id)"
check_out "object names" ids.txt "$CV_TEST_BUILDDIR/batch/exr_attr" out/m.exr cavalry.objectIds
check "objects named by ObjectBegin and file:line" \
    grep -qx '{"1":"quad_a","2":"mattes.pbrt:25"}' ids.txt
check_out "material names" mids.txt "$CV_TEST_BUILDDIR/batch/exr_attr" out/m.exr cavalry.materialIds
check "materials named by MakeNamedMaterial and file:line" \
    grep -q '"red".*"mattes.pbrt:24"' mids.txt

# Cryptomatte: header, ranked pairs that sum to alpha, a split edge pixel
for t in CryptoObject CryptoMaterial; do
    check "$t: coverage sums to alpha in every pixel, ranked" "$probe" sums out/m.exr $t
done
check "hash attribute" sh -c "'$CV_TEST_BUILDDIR/batch/exr_attr' out/m.exr cryptomatte/3ae39a5/hash | grep -qx MurmurHash3_32"
check "conversion attribute" sh -c "'$CV_TEST_BUILDDIR/batch/exr_attr' out/m.exr cryptomatte/3ae39a5/conversion | grep -qx uint32_to_float32"
check "material type's name" sh -c "'$CV_TEST_BUILDDIR/batch/exr_attr' out/m.exr cryptomatte/be359d6/name | grep -qx CryptoMaterial"
check_out "rank 0 inside the instance" r0.txt "$probe" rank out/m.exr 1 2 CryptoObject 0
check "quad_a covers it" grep -qx "quad_a 1.0000" r0.txt
check_out "rank 1 there" r1.txt "$probe" rank out/m.exr 1 2 CryptoObject 1
check "nothing else" grep -qx -- "- 0.0000" r1.txt
check_out "edge pixel rank 0" e0.txt "$probe" rank out/m.exr 3 2 CryptoObject 0
check_out "edge pixel rank 1" e1.txt "$probe" rank out/m.exr 3 2 CryptoObject 1
check "the edge pixel splits between the two quads" sh -c \
    "cat e0.txt e1.txt | cut -d' ' -f1 | sort | tr '\n' ' ' | grep -qx 'mattes.pbrt:25 quad_a '"
check "about half each" sh -c "cat e0.txt e1.txt | awk '\$2 >= 0.35 && \$2 <= 0.65 { n++ } END { exit !(n == 2) }'"
check_out "edge pixel materials" m0.txt "$probe" rank out/m.exr 3 2 CryptoMaterial 0
check "material names in the manifest" grep -Eq "^(red|mattes.pbrt:24) 0\.[3-6]" m0.txt
check_out "background rank 0" b0.txt "$probe" rank out/m.exr 3 0 CryptoObject 0
check "background has no id" grep -qx -- "- 0.0000" b0.txt

cat >pngonly.yaml <<'Y'
version: 1
jobs:
  - name: p
    scene: mattes.pbrt
    formats: [png]
    alpha: true
    aovs: [crypto_object]
Y
check "Cryptomatte with formats [png] alone fails" sh -c "! '$CAVALRY_BATCH' --check pngonly.yaml 2>pngonly.err"
check "at the aovs key" grep -q "pngonly.yaml:7:11: job \"p\": aovs need the exr format" pngonly.err
done_testing
