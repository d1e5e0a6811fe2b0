#!/bin/sh
# render_test.sh: a small batch renders every job in both formats with the
# metadata --resume relies on; --resume skips finished jobs and redoes a
# changed one; --only and --dry-run do what they say; CAVALRY_STAGE_TIMES
# logs the stages' GPU times and the renderer's set-up steps when set to
# anything but 0; CAVALRY_BVH_ROUNDS and CAVALRY_BVH_SPLIT reach the BVH
# build (the CLI reads them, cli/knobs.c). The scene's Sampler gives the
# samples per pixel of a job that names none, and its type changes
# nothing: "independent" and "sobol" render the same bits (cavalry-batch(1)).
# -q leaves only errors on standard error; png.bits 16 writes 16-bit PNGs.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
data="$CV_TEST_DATA/batch"
exr_attr="$CV_TEST_BUILDDIR/batch/exr_attr"
exr_same="$CV_TEST_BUILDDIR/batch/exr_same"
probe="$CV_TEST_BUILDDIR/batch/exr_probe"
cp "$data/tiny.pbrt" "$data/jobs.yaml" "$tmp/"
cd "$tmp"

check_out "renders" run1.jsonl "$CAVALRY_BATCH" --progress=json jobs.yaml 2>run1.err
for f in out/a.exr out/a.png out/b.exr out/b.png out/c.png; do
    check "$f written" test -s "$f"
done
check "c has no EXR (png only)" test ! -e out/c.exr
check "no temporary files left" test -z "$(find out -name '.*.tmp')"
check "three jobs finished" test "$(grep -c '"event":"job_finished"' run1.jsonl)" -eq 3
check "json ends with batch_finished" sh -c 'tail -n 1 run1.jsonl | grep -q "\"event\":\"batch_finished\",.*\"done\":3"'
check "status complete" test "$("$exr_attr" out/a.exr cavalry.status)" = complete
check "job name recorded" test "$("$exr_attr" out/a.exr cavalry.job)" = a
check "settings hash recorded" sh -c "\"$exr_attr\" out/a.exr cavalry.settingsHash | grep -Eq '^[0-9a-f]{16}\$'"

check_out "resume skips all" run2.jsonl "$CAVALRY_BATCH" --progress=json --resume jobs.yaml 2>run2.err
check "three skipped" test "$(grep -c '"event":"job_skipped"' run2.jsonl)" -eq 3

sed 's/    spp: 2/    spp: 3/' jobs.yaml >jobs2.yaml && mv jobs2.yaml jobs.yaml
check_out "resume after a change" run3.jsonl "$CAVALRY_BATCH" --progress=json --resume jobs.yaml 2>run3.err
check "only the changed job renders" sh -c 'grep "\"event\":\"job_finished\"" run3.jsonl | grep -q "\"job\":\"b\"" && test "$(grep -c "\"event\":\"job_finished\"" run3.jsonl)" -eq 1'

check_out "--force renders again" run4.jsonl "$CAVALRY_BATCH" --progress=json --resume --force --only=c jobs.yaml 2>run4.err
check "--only renders one job" test "$(grep -c '"event":"job_finished"' run4.jsonl)" -eq 1

check_out "stage times on" run5.jsonl env CAVALRY_STAGE_TIMES=1 "$CAVALRY_BATCH" --progress=json --resume --force --only=c jobs.yaml 2>run5.err
check "CAVALRY_STAGE_TIMES=1 logs the stages" grep -q "stage intersect" run5.err
check "CAVALRY_STAGE_TIMES=1 logs the renderer's set-up" \
    grep -q "renderer set-up (each step waited for): programs .* ms, integrator state .* ms, path buffers .* ms (.* MB)" run5.err
check_out "stage times off" run6.jsonl env CAVALRY_STAGE_TIMES=0 "$CAVALRY_BATCH" --progress=json --resume --force --only=c jobs.yaml 2>run6.err
check "CAVALRY_STAGE_TIMES=0 logs none" sh -c '! grep -q "stage intersect\|renderer set-up" run6.err'
check "BVH knobs unset" "$CAVALRY_BATCH" -v --progress=none --resume --force --only=c jobs.yaml 2>run7.err
check "the BVH build gets the defaults" grep -q "3 treelet rounds, split budget 0.3)" run7.err
check "BVH knobs set" env CAVALRY_BVH_ROUNDS=1 CAVALRY_BVH_SPLIT=0.5 "$CAVALRY_BATCH" -v --progress=none --resume --force --only=c jobs.yaml 2>run8.err
check "the BVH build gets CAVALRY_BVH_ROUNDS and _SPLIT" grep -q "1 treelet rounds, split budget 0.5)" run8.err

# -q: errors only (cavalry-batch(1)); a scene warning shows without it
{ cat tiny.pbrt; printf 'Material "diffuse" "float bogus" 1\n'; } >warn.pbrt
printf 'version: 1\njobs:\n  - name: w\n    scene: warn.pbrt\n    output: q/{name}\n    formats: [png]\n    spp: 1\n    png: {bits: 16}\n' >warn.yaml
check "a scene with a warning renders" "$CAVALRY_BATCH" --progress=none warn.yaml 2>loud.err
check "without -q the warning shows" grep -q 'warning: .*warn.pbrt:.*"float bogus" unused' loud.err
check "-q renders" "$CAVALRY_BATCH" -q --progress=none --force warn.yaml 2>quiet.err
check "-q shows no warning nor information" test ! -s quiet.err
# png.bits 16 writes a 16-bit PNG: its header's bit depth (byte 24)
check "png.bits 16: the PNG's bit depth is 16" \
    test "$(od -An -tu1 -j24 -N1 q/w.png | tr -d ' ')" = 16

check_out "--dry-run" plan.txt "$CAVALRY_BATCH" --dry-run --resume jobs.yaml 2>plan.err
check "plan lists every job" test "$(grep -c '^[abc]: tiny.pbrt' plan.txt)" -eq 3
check "plan knows what is up to date" test "$(grep -c 'up to date' plan.txt)" -eq 3
printf 'version: 1\njobs:\n' >samplers.yaml
for t in sobol independent; do
    sed "s/^Sampler .*/Sampler \"$t\" \"integer pixelsamples\" [ 3 ]/" tiny.pbrt >$t.pbrt
    printf '  - name: %s\n    scene: %s.pbrt\n    output: smp/{name}\n    formats: [exr]\n' $t $t \
        >>samplers.yaml
    printf '    exr: {half: false}\n' >>samplers.yaml
done
check_out "jobs of the scene's samples per pixel render" smp.out "$CAVALRY_BATCH" samplers.yaml \
    2>smp.err
check "the Sampler's pixelsamples is their spp" \
    test "$("$probe" attr smp/sobol.exr cavalry.sppTarget)" = 3 -a \
    "$("$probe" attr smp/independent.exr cavalry.sppTarget)" = 3
check "the Sampler's type changes no bit" "$exr_same" smp/sobol.exr smp/independent.exr
done_testing
