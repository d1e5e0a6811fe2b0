#!/bin/sh
# rlpath_unguided_test.sh: rlpath builds a shade bin without its guide
# where none of the bin's materials is of a kind the guide serves
# (trace/shade_bins.h: cv_shade_bins_guided; tests/trace/rlpath_unguided_test
# checks what CV_RL_UNGUIDED leaves out): tiny.pbrt's floor with a glossy
# conductor (bin 1, alpha below 0.5) gets bin 1's program with
# CV_RL_UNGUIDED under both methods; with a rough conductor (alpha 0.6) it
# does not; path's programs never carry it. Every job renders.
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
cd "$tmp"

scene() {   # scene ROUGHNESS: tiny.pbrt with a conductor box of that alpha
    cat "$CV_TEST_DATA/batch/tiny.pbrt"
    printf 'Material "conductor" "float roughness" [ %s ] "bool remaproughness" false\n' "$1"
    printf 'Shape "trianglemesh" "point3 P" [ -0.5 0.5 0  0.5 0.5 0  0.5 0.5 1  -0.5 0.5 1 ]\n'
    printf '    "integer indices" [ 0 2 1  0 3 2 ]\n'
}
job() {   # job NAME SCENE INTEGRATOR-LINES
    printf 'version: 1\njobs:\n  - name: %s\n    scene: %s\n' "$1" "$2"
    printf '    output: out/{name}\n    formats: [exr]\n    spp: 4\n%s\n' "$3"
}
scene 0.1 >glossy.pbrt
scene 0.6 >rough.pbrt
bin1='shade.comp \[[^]]*CV_SHADE_BIN=1[^]]*\]'
for m in qlearn sdtree; do
    for s in glossy rough; do
        job "$m-$s" "$s.pbrt" "    integrator: rlpath
    rlpath: {method: $m}" >"$m-$s.yaml"
        check_out "$m on the $s conductor renders" "$m-$s.out" "$CAVALRY_BATCH" -v "$m-$s.yaml" \
            2>"$m-$s.err"
        check "$m, $s: bin 1's program was built" grep -q "$bin1" "$m-$s.err"
    done
    check "$m: the glossy conductor's bin is built without the guide" \
        sh -c "grep '$bin1' $m-glossy.err | grep -q CV_RL_UNGUIDED"
    check "$m: the rough conductor's is not" \
        sh -c "! grep '$bin1' $m-rough.err | grep -q CV_RL_UNGUIDED"
done
job path glossy.pbrt "    integrator: path" >path.yaml
check_out "path renders" path.out "$CAVALRY_BATCH" -v path.yaml 2>path.err
check "and none of its programs carries CV_RL_UNGUIDED" sh -c "! grep -q CV_RL_UNGUIDED path.err"
done_testing
