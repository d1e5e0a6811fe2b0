#!/bin/sh
# relight_test.sh: env.scale, env.rotate and lights.scale (cavalry-manifest(5))
# change the image as the same change written into the scene would, on the
# scene loaded and built once: with the same seed, light selection and
# samples stay the same, so twice the light is exactly twice the pixels,
# and the environment turned by env.rotate is the environment turned by
# the scene's own Rotate; env.file shows another image in the environment,
# read as the scene's own map is. lights.scale takes at most 32 lights, each
# named once (also when spelt "0" and "00"), anything else an error at its
# line and column.
. "${srcdir:-.}/tests/setup.sh"
data="$CV_TEST_DATA/batch"
exr_scale="$CV_TEST_BUILDDIR/batch/exr_scale"
cd "$tmp"

"$CAVALRY_BATCH" --dump-scene="$data/env.pbrt" >dump.txt
check "--dump-scene names the light directives" \
    sh -c "grep -q '^  light-source 0 infinite lights 1\$' dump.txt &&
           grep -q '^  light-source 1 point lights 1\$' dump.txt"
"$CAVALRY_BATCH" --dump-scene="$data/tiny.pbrt" >dump_tiny.txt
check "--dump-scene: an area light's directive names its triangles' lights" \
    grep -q '^  light-source 0 area diffuse lights 2$' dump_tiny.txt

# lights.scale: at most 32 lights, each once. many.pbrt has 32 light
# directives: the area light of tiny.pbrt and 31 dim point lights.
cp "$data/tiny.pbrt" many.pbrt
for i in $(seq 1 31); do
    echo "LightSource \"point\" \"rgb I\" [ 0.02 0.02 0.02 ] \"point3 from\" [ $i 1 0 ]"
done >>many.pbrt
all32=$(seq 0 31 | sed 's/$/: 0.5/' | tr '\n' ',' | sed 's/,$//')
all33=$(seq 0 32 | sed 's/$/: 0.5/' | tr '\n' ',' | sed 's/,$//')
# lights_check SCALES: --check of a job on many.pbrt with lights.scale SCALES
lights_check() {
    printf 'version: 1\njobs:\n  - name: a\n    scene: many.pbrt\n    lights: {scale: {%s}}\n' \
        "$1" >lights.yaml
    "$CAVALRY_BATCH" --check lights.yaml >lights.out 2>lights.err
}
check "lights.scale: 32 lights named are valid" lights_check "$all32"
lights_check "$all33" && rc=0 || rc=$?
check "lights.scale: 33 lights named: exit 3 (got $rc)" test "$rc" -eq 3
check "lights.scale: 33 lights named: at the mapping's line:col" \
    grep -qx 'error: lights.yaml:5:21: lights.scale: 33 lights named; at most 32' lights.err
lights_check "0: 2, 1: 1, 0: 3" && rc=0 || rc=$?
check "lights.scale: a light named twice: exit 3 (got $rc)" test "$rc" -eq 3
check "lights.scale: a light named twice: a duplicate key at its line:col" \
    grep -qx 'error: lights.yaml:5:34: duplicate key "0" (first given at line 5)' lights.err
lights_check "0: 2, 1: 1, 00: 3" && rc=0 || rc=$?
check "lights.scale: a light named twice, spelt two ways: exit 3 (got $rc)" test "$rc" -eq 3
check "lights.scale: a light named twice, spelt two ways: at its line:col" grep -qx \
    'error: lights.yaml:5:34: lights.scale: light 0 is named twice (first given as "0" at line 5)' \
    lights.err

"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
cat >m.yaml <<Y
version: 1
defaults:
  scene: $data/env.pbrt
  output: out/{name}
  spp: 2
  seed: 3
  exr: {half: false}
jobs:
  - name: base
  - name: twice
    lights: {scale: {0: 2, 1: 2}}
  - name: no_point
    lights: {scale: {1: 0}}
  - name: env
    matrix:
      lights.scale: {env_only: {1: 0}}
      env.scale: [1, 2]
  - name: env_seed
    seed: 4
    lights: {scale: {1: 0}}
    env: {scale: 2}
  - name: turned
    env: {rotate: [90, 0, 1, 0]}
  - name: turned_scene
    scene: $data/env_turned.pbrt
Y
check_out "renders" run.jsonl "$CAVALRY_BATCH" --progress=json m.yaml
check "one load of env.pbrt for 7 jobs" \
    test "$(grep '"phase":"scene_load"' run.jsonl | grep -c 'env.pbrt')" -eq 1
check "one BVH build of env.pbrt" \
    test "$(grep '"phase":"bvh_build"' run.jsonl | grep -c 'env.pbrt')" -eq 1
check "every light twice as bright: every pixel twice" \
    "$exr_scale" times out/base.exr out/twice.exr 2 1e-5
check "env.scale 2 on an environment-only image: every pixel twice" \
    "$exr_scale" times out/env_env_only_1.exr out/env_env_only_2.exr 2 1e-5
m1=$("$exr_scale" mean out/env_env_only_1.exr)
m2=$("$exr_scale" mean out/env_seed.exr)
check "env.scale 2, another seed: the mean doubles within noise ($m1, $m2)" \
    awk -v a="$m1" -v b="$m2" 'BEGIN { r = b / (2 * a); exit !(r > 0.9 && r < 1.1) }'
mb=$("$exr_scale" mean out/base.exr)
mn=$("$exr_scale" mean out/no_point.exr)
check "lights.scale {1: 0} takes the point light away ($mb, $mn)" \
    awk -v a="$mb" -v b="$mn" 'BEGIN { exit !(b < a && b > 0.5 * a) }'
check "env.rotate = the scene's own Rotate" \
    "$exr_scale" times out/turned_scene.exr out/turned.exr 1 1e-4
check "env.rotate changes the image" \
    sh -c "! '$exr_scale' times out/base.exr out/turned.exr 1 1e-2 2>/dev/null"

# 32 lights, each halved: every pixel halved
cat >half.yaml <<Y
version: 1
defaults: {scene: many.pbrt, output: "out/{name}", spp: 2, seed: 3, resolution: [8, 6],
           formats: [exr], exr: {half: false}}
jobs:
  - name: many
  - name: many_half
    lights: {scale: {$all32}}
Y
check "32 lights scaled: renders" "$CAVALRY_BATCH" --progress=none half.yaml
check "32 lights, each halved: every pixel halved" \
    "$exr_scale" times out/many.exr out/many_half.exr 0.5 1e-5

# env.file: the scene's own image again changes nothing; a uniform grey map
# lights as a constant environment of its value does
sed 's|"string filename" "../trace/oracle/envmap.pfm"|"rgb L" [ 0.5 0.5 0.5 ]|' "$data/env.pbrt" \
    >const.pbrt
cat >files.yaml <<Y
version: 1
defaults:
  scene: $data/env.pbrt
  output: out/{name}
  spp: 2
  seed: 3
  exr: {half: false}
  lights: {scale: {1: 0}}
jobs:
  - name: own
  - name: file
    matrix:
      env.file: {same: $data/../trace/oracle/envmap.pfm, grey: $data/gray.pfm}
  - name: const
    scene: const.pbrt
Y
check_out "env.file renders" files.jsonl "$CAVALRY_BATCH" --progress=json files.yaml
check "env.file: one load and one BVH build of env.pbrt for 3 jobs" \
    test "$(grep '"phase":"scene_load"' files.jsonl | grep -c 'env.pbrt')" -eq 1 -a \
         "$(grep '"phase":"bvh_build"' files.jsonl | grep -c 'env.pbrt')" -eq 1
check "env.file naming the scene's own image: the same pixels" \
    "$exr_scale" times out/own.exr out/file_same.exr 1 1e-6
mg=$("$exr_scale" mean out/file_grey.exr)
mc=$("$exr_scale" mean out/const.exr)
check "env.file of a uniform 0.5 map = a constant 0.5 environment within noise ($mg, $mc)" \
    awk -v a="$mg" -v b="$mc" 'BEGIN { r = a / b; exit !(r > 0.9 && r < 1.1) }'

cat >bad.yaml <<Y
version: 1
jobs:
  - name: a
    scene: $data/tiny.pbrt
    env: {scale: 2}
  - name: b
    scene: $data/env.pbrt
    matrix:
      lights.scale: [{1: 2}, {2: 1}]
  - name: c
    scene: $data/env.pbrt
    env: {file: $data/wide.pfm}
  - name: d
    scene: const.pbrt
    env: {file: $data/wide.pfm}
Y
set +e
"$CAVALRY_BATCH" --check bad.yaml >bad.out 2>bad.err
rc=$?
set -e
check "overrides the scene cannot take: exit 3 (got $rc)" test "$rc" -eq 3
check "env.scale without an environment, at its place" \
    grep -qF 'bad.yaml:5:18: job "a": the scene has no environment light' bad.err
check "a light the scene lacks, at its place in the matrix" \
    grep -qF 'bad.yaml:9:30: job "b_1": lights.scale: the scene has no light 2' bad.err
check "a non-square image for an equal-area environment, at its place" \
    grep -qF 'bad.yaml:12:17: job "c": env.file: "'"$data"'/wide.pfm" is 8x4;' bad.err
check "a colour environment takes a latitude-longitude image" sh -c '! grep -q "job \"d\"" bad.err'
cat >missing.yaml <<Y
version: 1
jobs:
  - name: a
    scene: $data/env.pbrt
    env: {file: nothere.exr}
Y
set +e
"$CAVALRY_BATCH" --check missing.yaml >missing.out 2>missing.err
set -e
check "a missing env.file, at its place" \
    grep -qF 'missing.yaml:5:17: job "a" (line 3): environment image "nothere.exr" not found' \
    missing.err
done_testing
