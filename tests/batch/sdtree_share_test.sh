#!/bin/sh
# sdtree_share_test.sh: rlpath's sdtree method guides the trees that only
# serve further training with cv_sdtree_defaults.train_mix and the tree the
# render keeps with its mix (src/trace/sdtree.c); a mix set in the job
# applies to every tree (cavalry-manifest(5), rlpath's mix). Read from the
# debug line of each build ("rlpath sdtree N: ... share S)").
. "${srcdir:-.}/tests/setup.sh"
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
cp "$CV_TEST_DATA/batch/cornell_box.pbrt" "$tmp/"
cd "$tmp"

job() {   # job NAME RLPATH: a manifest of one 24-spp rlpath job
    printf 'version: 1\njobs:\n  - name: %s\n    scene: cornell_box.pbrt\n' "$1"
    printf '    output: out/{name}\n    formats: [exr]\n    resolution: [32, 32]\n'
    printf '    seed: 3\n    spp: 24\n    integrator: rlpath\n    rlpath: %s\n' "$2"
}
shares() {   # shares LOG: the share of each build, in order, on one line
    sed -n 's/.*rlpath sdtree [0-9]*: .*, share \([0-9.]*\)).*/\1/p' "$1" | tr '\n' ' '
}

# render NAME RLPATH: renders the job with -v; $s: its builds' shares
render() {
    job "$1" "$2" >"$1.yaml"
    check_out "sdtree renders ($2)" "$1.out" "$CAVALRY_BATCH" -v "$1.yaml" 2>"$1.err"
    s=$(shares "$1.err")
    echo "# $1: $s"
    check "it builds at least two trees" test "$(echo $s | wc -w)" -ge 2
}

render def '{method: sdtree, train: 16}'
check "the last, which the render keeps, guides with 0.7" \
    test "$(echo $s | awk '{ print $NF }')" = 0.7
check "every earlier one with 0.3" \
    sh -c "echo '$s' | awk '{ for (i = 1; i < NF; i++) if (\$i != \"0.3\") exit 1 }'"

render set '{method: sdtree, train: 16, mix: 0.5}'
check "every one guides with 0.5" \
    sh -c "echo '$s' | awk '{ for (i = 1; i <= NF; i++) if (\$i != \"0.5\") exit 1 }'"
done_testing
