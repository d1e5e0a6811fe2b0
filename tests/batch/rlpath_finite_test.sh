#!/bin/sh
# rlpath_finite_test.sh: rlpath learns with float atomics and is not
# bit-reproducible on llvmpipe (pass sizes follow the wall clock, and the
# order of the atomic adds follows the threads), so one render proves
# little: the Cornell box (scene-v4.pbrt of /work/shared/scenes, CC0) at
# 32x32, 8 spp, seed 3 is rendered 24 times, as in the report of an
# all-black image from such a job, and every image must be lit (mean red
# near the 0.2 these settings give) with no NaN or infinite value, every
# job finished without a warning. Then a lamp near the float limit, whose
# sums overflow, must be reported (log, the job's detail) rather than
# written in silence.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
probe="$CV_TEST_BUILDDIR/batch/exr_probe"
cp "$data/cornell_box.pbrt" "$tmp/"
cd "$tmp"

jobs() {   # jobs SCENE N: a manifest of N equal rlpath jobs
    printf 'version: 1\ndefaults:\n  scene: %s\n  output: out/{name}\n' "$1"
    printf '  formats: [exr]\n  exr: {half: false}\n  resolution: [32, 32]\n'
    printf '  spp: 8\n  seed: 3\n  integrator: rlpath\njobs:\n'
    i=1
    while [ "$i" -le "$2" ]; do
        printf '  - name: r%s\n' "$i"
        i=$((i + 1))
    done
}

jobs cornell_box.pbrt 8 >rl.yaml
dark=0 nonfinite=0 rendered=0
for run in 1 2 3; do
    check_out "batch $run renders" run$run.jsonl "$CAVALRY_BATCH" --progress=json rl.yaml \
        2>run$run.err
    check "batch $run: no job reports a detail" sh -c "! grep -q '\"detail\"' run$run.jsonl"
    check "batch $run: no warning" sh -c "! grep -q 'NaN or infinite' run$run.err"
    for f in out/r*.exr; do
        s=$("$probe" stats "$f") || s="unreadable"
        rendered=$((rendered + 1))
        # "mean R G B nonfinite N"
        set -- $s
        good=1
        [ "${5:-}" = nonfinite ] && [ "$6" -eq 0 ] || { nonfinite=$((nonfinite + 1)); good=0; }
        awk -v r="${2:-0}" 'BEGIN { exit !(r > 0.15 && r < 0.25) }' || { dark=$((dark + 1)); good=0; }
        [ "$good" -eq 1 ] || echo "# batch $run $f: $s"
    done
    rm -rf out
done
check "24 images rendered ($rendered)" test "$rendered" -eq 24
check "no image dark or wrong in brightness ($dark of $rendered)" test "$dark" -eq 0
check "no image with a NaN or infinite value ($nonfinite of $rendered)" test "$nonfinite" -eq 0

sed 's/"rgb L" \[ 17 12 4 \]/"rgb L" [ 3e38 3e38 3e38 ]/' cornell_box.pbrt >hot.pbrt
check "the hot lamp is in the scene" grep -q 3e38 hot.pbrt
jobs hot.pbrt 1 >hot.yaml
check_out "a lamp at the float limit renders" hot.jsonl "$CAVALRY_BATCH" --progress=json hot.yaml \
    2>hot.err
check "its overflow is a warning" grep -q 'NaN or infinite and left out' hot.err
check "and the job's detail" sh -c "grep '\"job_finished\"' hot.jsonl | grep -q 'NaN or infinite'"
check "no NaN or infinite value is written" sh -c "\"$probe\" stats out/r1.exr | grep -q 'nonfinite 0\$'"
done_testing
