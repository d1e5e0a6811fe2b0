#!/bin/sh
# matrix_test.sh: a job's matrix (cavalry-manifest(5), "Matrix") expands it
# into one job per combination of its lists, first key slowest, each with
# its name, output template values, settings hash, --only name, shard and
# lock; an expanded job renders as the same job written out by hand; the
# scene of all of them is loaded and its BVH built once; and every misfit
# is reported at the line and column where it is written.
. "${srcdir:-.}/tests/setup.sh"
data="$CV_TEST_DATA/batch"
exr_same="$CV_TEST_BUILDDIR/batch/exr_same"
exr_probe="$CV_TEST_BUILDDIR/batch/exr_probe"
cp "$data/tiny.pbrt" "$tmp/"
cd "$tmp"

cat >m.yaml <<'Y'
version: 1
defaults:
  scene: tiny.pbrt
  spp: 1
  formats: [exr]
jobs:
  - name: shot
    output: out/{camera.fov}/{name}_s{seed}
    matrix:
      camera.fov: {wide: 60, tight: 20}
      seed: [1, 2, 3]
  - name: plain
    output: out/plain
    camera: {fov: 20}
    seed: 2
Y
"$CAVALRY_BATCH" --dry-run m.yaml >dry.txt
cut -d: -f1 dry.txt >names.txt
printf '%s\n' shot_wide_1 shot_wide_2 shot_wide_3 shot_tight_1 shot_tight_2 shot_tight_3 plain \
    >want.txt
check "dry run: 2 x 3 jobs, first key slowest, then the plain job" cmp -s names.txt want.txt
check "dry run: output template with {camera.fov} and {seed}" \
    grep -q "^shot_tight_2: tiny.pbrt -> out/tight/shot_tight_2_s2 \[exr\]" dry.txt
check "dry run: the matrix values of a job" \
    grep -qF "(matrix of shot: camera.fov=tight, seed=2)" dry.txt
"$CAVALRY_BATCH" --dry-run --json m.yaml >dry.json
check "dry run json: matrix_of and the values" \
    grep -qF '"name":"shot_wide_3",' dry.json
check "dry run json: matrix of shot_wide_3" \
    grep -qF '"matrix_of":"shot","matrix":{"camera.fov":"wide","seed":"3"}' dry.json
hash_of() { grep "\"name\":\"$1\"" dry.json | sed 's/.*"settings_hash":"\([0-9a-f]*\)".*/\1/'; }
check "each expanded job has its own settings hash" \
    test "$(hash_of shot_wide_1)" != "$(hash_of shot_wide_2)" -a \
         "$(hash_of shot_wide_1)" != "$(hash_of shot_tight_1)"
"$CAVALRY_BATCH" --dry-run m.yaml --only shot >only.txt
check "--only NAME takes every job of its matrix" test "$(wc -l <only.txt)" -eq 6
"$CAVALRY_BATCH" --dry-run m.yaml --only 'shot_tight_*' >only.txt
check "--only with a glob over expanded names" test "$(cut -d: -f1 only.txt | tr '\n' ' ')" = \
    "shot_tight_1 shot_tight_2 shot_tight_3 "
: >union.txt
for i in 0 1 2; do
    "$CAVALRY_BATCH" --dry-run --shard-index=$i --shard-count=3 m.yaml | cut -d: -f1 >>union.txt
done
sort want.txt >want.sorted
sort union.txt >union.sorted
check "3 shards cover the 7 jobs exactly once" cmp -s want.sorted union.sorted

GPU=yes
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || GPU=
if [ -n "$GPU" ]; then
    check_out "renders" run.jsonl "$CAVALRY_BATCH" --progress=json m.yaml
    check "one scene load for 7 jobs" test "$(grep -c '"phase":"scene_load"' run.jsonl)" -eq 1
    check "one BVH build for 7 jobs" test "$(grep -c '"phase":"bvh_build"' run.jsonl)" -eq 1
    check "7 jobs done" test "$(grep -c '"event":"job_finished"' run.jsonl)" -eq 7
    check "an expanded job's seed is its value" \
        test "$("$exr_probe" attr out/wide/shot_wide_3_s3.exr cavalry.seed)" = 3
    check "an expanded job = the same job written out" \
        "$exr_same" out/tight/shot_tight_2_s2.exr out/plain.exr
    check "seeds give other images" \
        sh -c "! '$exr_same' out/tight/shot_tight_1_s1.exr out/tight/shot_tight_2_s2.exr 2>/dev/null"
    check "each expanded job has its lock" test -e out/tight/.shot_tight_2_s2.lock
    "$CAVALRY_BATCH" --progress=json --resume m.yaml >resume.jsonl
    check "--resume skips every expanded job" \
        test "$(grep -c '"event":"job_skipped"' resume.jsonl)" -eq 7
    sed 's/seed: \[1, 2, 3\]/seed: [1, 2, 3, 4]/' m.yaml >m4.yaml
    "$CAVALRY_BATCH" --progress=json --resume m4.yaml >resume4.jsonl
    check "--resume renders only the values added to a list" \
        test "$(grep '"event":"job_finished"' resume4.jsonl | grep -c '"job":"shot_[a-z]*_4"')" -eq 2 -a \
             "$(grep -c '"event":"job_finished"' resume4.jsonl)" -eq 2
else
    ok "render checks # SKIP no GPU context"
fi

# expect_invalid NAME WANTED-MESSAGE...: --check of NAME.yaml fails with each
expect_invalid() {
    f=$1
    shift
    set +e
    "$CAVALRY_BATCH" --check "$f.yaml" >"$f.out" 2>"$f.err"
    rc=$?
    set -e
    check "$f: exit status 3 (got $rc)" test "$rc" -eq 3
    for want in "$@"; do
        check "$f: says \"$want\"" grep -qF -- "$want" "$f.err"
    done
}
cat >bad.yaml <<'Y'
version: 1
defaults: {scene: tiny.pbrt, spp: 1}
jobs:
  - name: a
    seed: 4
    matrix:
      seed: [1, 2]
      sed: [1]
      spp: []
      camera.fov: [30, 200]
      name: [x]
  - name: b
    matrix:
      max_depth: [1, 2, 1]
      scene: [sub/tiny.pbrt]
      integrator: [path, sppm]
  - name: c
    output: "{name}_{seed}"
  - name: d
    matrix: {seed: []}
  - name: e
    matrix: seed
Y
expect_invalid bad \
    'bad.yaml:7:7: matrix: "seed" is also a key of the job (line 5)' \
    'bad.yaml:8:7: unknown key "sed" in matrix' \
    'bad.yaml:9:12: matrix: spp: the list is empty' \
    'bad.yaml:10:24: camera.fov: expected a number from 0 to 180, got "200"' \
    'bad.yaml:11:7: matrix: "name" cannot vary in a matrix' \
    'bad.yaml:14:25: matrix: max_depth: value "1" is listed twice' \
    'bad.yaml:15:15: matrix: scene: "sub/tiny.pbrt" cannot label a job name' \
    'bad.yaml:16:26: integrator: expected one of path, rlpath, volpath, bdpt, got "sppm"' \
    'bad.yaml:18:13: job "c" (line 17): output "{name}_{seed}": {seed} is not a key' \
    'bad.yaml:20:20: matrix: seed: the list is empty' \
    'bad.yaml:22:13: matrix: expected a mapping of keys to lists of values'

# past the cap: 300 x 300 = 90000 jobs
seq 1 300 | tr '\n' ',' | sed 's/,$//' >list.txt
printf 'version: 1\njobs:\n  - name: big\n    scene: tiny.pbrt\n    matrix:\n      seed: [%s]\n      max_depth: [%s]\n' \
    "$(cat list.txt)" "$(cat list.txt)" >cap.yaml
expect_invalid cap 'cap.yaml:6:7: matrix: expands the job into more than 65536 jobs'

# names from two jobs' matrices that meet
cat >dup.yaml <<'Y'
version: 1
defaults: {scene: tiny.pbrt}
jobs:
  - name: a
    matrix: {seed: [1, 2]}
  - name: a_2
Y
expect_invalid dup 'dup.yaml:6:11: duplicate job name "a_2"'

# a value the plan refuses is reported at its place in the list
cat >plan.yaml <<'Y'
version: 1
jobs:
  - name: p
    scene: tiny.pbrt
    matrix:
      lights.scale: [{0: 2}, {5: 1}]
Y
expect_invalid plan 'plan.yaml:6:30: job "p_1": lights.scale: the scene has no light 5'
done_testing
