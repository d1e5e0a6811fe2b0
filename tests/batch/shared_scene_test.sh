#!/bin/sh
# shared_scene_test.sh: a batch uploads a scene and builds its BVH once for
# all the jobs on it, and sharing changes no pixel: a job rendered after
# others on the same scene (one with a resolution override) matches the same
# job rendered alone.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
exr_same="$CV_TEST_BUILDDIR/batch/exr_same"
cp "$data/tiny.pbrt" "$data/jobs.yaml" "$tmp/"
cd "$tmp"

check "jobs.yaml renders" "$CAVALRY_BATCH" --progress=none -v -v jobs.yaml 2>run1.err
check "three jobs, one BVH build" test "$(grep -c 'building BVH for' run1.err)" -eq 1

cat >twice.yaml <<'YAML'
version: 1
defaults:
  scene: tiny.pbrt
  output: out/{name}
  formats: [exr]
  spp: 4
  seed: 7
jobs:
  - name: small
    resolution: [8, 6]
  - name: a
  - name: a2
YAML
check "twice.yaml renders" "$CAVALRY_BATCH" --progress=none -v -v twice.yaml 2>run2.err
check "one BVH build for three jobs" test "$(grep -c 'building BVH for' run2.err)" -eq 1
mv out together
check "job a alone renders" "$CAVALRY_BATCH" --progress=none --only=a twice.yaml 2>run3.err
check "a after other jobs = a alone" "$exr_same" together/a.exr out/a.exr
check "a2 = a alone" "$exr_same" together/a2.exr out/a.exr
check "the override job's film differs" sh -c "! \"$exr_same\" together/small.exr out/a.exr 2>/dev/null"
done_testing
