#!/bin/sh
# resume_stale_test.sh: issue 25 section 2. --resume skips a job only when
# its outputs are up to date and intact: the settings hash covers every
# file the scene reads (an Include, a texture), a job's env.file image (its
# modification time, its size) and the effective OCIO config ($OCIO); a
# header-only EXR or a PNG with a flipped byte is rendered again; an image
# stopped by its time limit says so (cavalry.status: time-limit, with the
# spp reached and asked for) and is rendered again; a killed writer's
# temporary file is removed by the next write of that name. Skips are read
# from --dry-run --resume.
. "${srcdir:-.}/tests/setup.sh"
exr_attr="$CV_TEST_BUILDDIR/batch/exr_attr"
data="$CV_TEST_DATA/batch"
cd "$tmp"
sed '/^WorldBegin/a Include "inc.pbrt"' "$data/tiny.pbrt" >main.pbrt
printf 'version: 1\njobs:\n  - name: t\n    scene: tiny.pbrt\n    formats: [png]\n    output: tex\n' \
    >seed.yaml
cp "$data/tiny.pbrt" .
"$CAVALRY_BATCH" --progress=none seed.yaml 2>/dev/null
cat >inc.pbrt <<'P'
Texture "t" "spectrum" "imagemap" "string filename" "tex.png"
Material "diffuse" "texture reflectance" "t"
P
cp "$CAVALRY_DATA_DIR/configs/cavalry.ocio" my.ocio
cat >jobs.yaml <<'Y'
version: 1
defaults: {scene: main.pbrt, output: "out/{name}"}
jobs:
  - name: a
    formats: [exr, png]
Y
# skipped NAME: --dry-run --resume would skip job a
skipped() {
    OCIO="$tmp/my.ocio" "$CAVALRY_BATCH" --dry-run --resume jobs.yaml >plan.txt 2>plan.err
    grep -q '^a: .*(up to date: skipped)' plan.txt
}
not_skipped() { ! skipped; }
render() { OCIO="$tmp/my.ocio" "$CAVALRY_BATCH" --progress=none jobs.yaml 2>render.err || cat render.err; }
render
check "rendered" test -s out/a.exr -a -s out/a.png
check "up to date after rendering" skipped

# inputs: a change that keeps the top scene file as it was
touch -r main.pbrt main.ref
echo '# changed' >>inc.pbrt
touch -d '2001-01-01' inc.pbrt
check "an Include changed: rendered again" not_skipped
render
check "up to date again" skipped
cp tex.png tex.old && printf 'x' >>tex.png && touch -d '2002-02-02' tex.png
check "a texture changed: rendered again" not_skipped
cp tex.old tex.png
render
echo '# changed' >>my.ocio
touch -d '2003-03-03' my.ocio
check "the \$OCIO config changed: rendered again" not_skipped
render

# env.file: its size and modification time enter the settings hash
# (cavalry-manifest(5)), named relative to a manifest in another folder
mkdir -p envjob
cp "$data/gray.pfm" envjob/sky.pfm
printf 'version: 1\njobs:\n  - {name: e, scene: %s, env: {file: sky.pfm}, spp: 1, formats: [exr], output: "out/{name}"}\n' \
    "$data/env.pbrt" >envjob/env.yaml
env_skipped() {
    "$CAVALRY_BATCH" --dry-run --resume envjob/env.yaml >env_plan.txt 2>env_plan.err
    grep -q '^e: .*(up to date: skipped)' env_plan.txt
}
env_not_skipped() { ! env_skipped; }
env_render() { "$CAVALRY_BATCH" --progress=none envjob/env.yaml 2>env_render.err || cat env_render.err; }
env_render
check "env.file: rendered" test -s envjob/out/e.exr
check "env.file: up to date after rendering" env_skipped
touch -d '2004-04-04' envjob/sky.pfm
check "env.file touched: rendered again" env_not_skipped
env_render
check "env.file: up to date again" env_skipped
# another image of another size, under the old modification time
cp "$data/../trace/oracle/envmap.pfm" envjob/sky.pfm
touch -d '2004-04-04' envjob/sky.pfm
check "env.file changed in size only: rendered again" env_not_skipped
env_render
check "env.file: up to date once more" env_skipped

# damaged outputs
cp out/a.exr good.exr
head -c 1000 good.exr >out/a.exr
check "a header-only EXR: rendered again" not_skipped
cp good.exr out/a.exr
check "the intact EXR is up to date" skipped
cp out/a.png good.png
size=$(wc -c <good.png)
# flip one byte inside the image data, away from the metadata at the start
off=$((size - 20))
byte=$(od -An -tu1 -j"$off" -N1 good.png | tr -d ' ')
printf "$(printf '\\%03o' $((byte ^ 1)))" |
    dd of=out/a.png bs=1 seek="$off" conv=notrunc 2>/dev/null
check "the flipped byte is flipped" sh -c '! cmp -s good.png out/a.png'
check "a PNG with a flipped byte: rendered again" not_skipped
cp good.png out/a.png
check "the intact PNG is up to date" skipped

# a stale temporary file of a killed writer
echo junk >out/.a.exr.k1ll3d.tmp
echo keep >out/.other.exr.k1ll3d.tmp
render
check "stale temporary file removed" test ! -e out/.a.exr.k1ll3d.tmp
check "another name's file kept" test -e out/.other.exr.k1ll3d.tmp

# stopped by the time limit
cat >limit.yaml <<'Y'
version: 1
jobs:
  - name: l
    scene: tiny.pbrt
    spp: 16777216
    time_limit: 0.001
Y
"$CAVALRY_BATCH" --progress=none limit.yaml 2>limit.err
check "time limit: status says so" test "$("$exr_attr" l.exr cavalry.status)" = time-limit
check "time limit: spp asked recorded" sh -c "strings l.exr | grep -q sppTarget"
"$CAVALRY_BATCH" --dry-run --resume limit.yaml >limit.txt 2>&1
check "time limit: --resume renders it again" sh -c '! grep -q "up to date" limit.txt'
done_testing
