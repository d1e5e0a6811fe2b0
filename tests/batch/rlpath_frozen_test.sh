#!/bin/sh
# rlpath_frozen_test.sh: a job of rlpath's sdtree method renders its
# passes after training with the programs built without the learning code
# (trace/integrator.h: frozen_programs; tests/trace/rlpath_frozen_test
# checks what those programs hold; the 16 spp after training here are the
# first, guided sub-pass of the guide's choice at 8 slots a pixel,
# trace/guide_choice.h, so no pass runs path's programs): the Cornell box
# (scene-v4.pbrt of /work/shared/scenes, CC0; bin 0 alone) switches its
# shade and shadow stages once, at the end of training, and its misses
# from the learning escaped stage to the intersect stage (the box is open
# to the camera: trace/render.h, enum cv_misses), and its image is lit
# (mean red near the 0.2 these settings give) and finite. A job that
# ends within its training, and a Q-learning job (which keeps one build of
# its shade stage), never switch.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
probe="$CV_TEST_BUILDDIR/batch/exr_probe"
cp "$CV_TEST_DATA/batch/cornell_box.pbrt" "$tmp/"
cd "$tmp"

job() {   # job NAME SPP RLPATH: a manifest of one rlpath job
    printf 'version: 1\njobs:\n  - name: %s\n    scene: cornell_box.pbrt\n' "$1"
    printf '    output: out/{name}\n    formats: [exr]\n    exr: {half: false}\n'
    printf '    resolution: [32, 32]\n    seed: 3\n    spp: %s\n' "$2"
    printf '    integrator: rlpath\n    rlpath: %s\n' "$3"
}
# (a pattern: "guide's" without the quote the checks below wrap it in)
switched='passes after learning: 2 stage programs of the guide.s, without the learning code'

job sd 24 '{method: sdtree, train: 8}' >sd.yaml
check_out "sdtree renders" sd.out "$CAVALRY_BATCH" -v sd.yaml 2>sd.err
check "it switches to the frozen programs once" \
    test "$(grep -c "$switched" sd.err)" -eq 1
check "their builds were asked for with CV_FROZEN" grep -q 'sd_shade.comp \[.*CV_FROZEN\]' sd.err
check "and its misses start anew in the intersect stage" \
    grep -q 'misses: .* left the scene: started in the intersect stage' sd.err
s=$("$probe" stats out/sd.exr) || s=unreadable
echo "# sd: $s"
set -- $s
check "its image is finite" test "${5:-}" = nonfinite -a "${6:-1}" -eq 0
check "and lit (mean red ${2:-?})" awk -v r="${2:-0}" 'BEGIN { exit !(r > 0.15 && r < 0.25) }'

job short 8 '{method: sdtree, train: 8}' >short.yaml
check_out "a job within its training renders" short.out "$CAVALRY_BATCH" -v short.yaml \
    2>short.err
check "and never switches" sh -c "! grep -q '$switched' short.err"

job q 24 '{train: 8}' >q.yaml
check_out "Q-learning renders" q.out "$CAVALRY_BATCH" -v q.yaml 2>q.err
check "and keeps its one build" sh -c "! grep -q 'passes after learning' q.err"
done_testing
