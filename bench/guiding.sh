#!/bin/sh
# guiding.sh: path against rlpath at equal wall time (issue 29). Every
# render is a cavalry-batch job stopped by --time-limit (which counts from
# the job's start: scene load and BVH included, the same for every variant;
# the program cache is warmed first, so no render pays a compile). Each
# image's relMSE is taken against a converged reference (a long path render
# made here once per scene and size, kept in the work folder), then the
# medians over the seeds go to a table and a log-log plot of relMSE against
# time per scene.
#
# usage: bench/guiding.sh [--batch PATH] [--bench PATH] [--scenes DIR]
#                         [--times "2 4 8"] [--spp N] [--seeds "1 2 3"]
#                         [--size WxH] [--ref-spp N] [--room-triangles N]
#                         [--variants "path rlpath rlpath-online"]
#                         [--rl "KEY: V, ..."] [--work DIR] [--summarize]
#                         [scenes...]
#   --batch PATH   cavalry-batch (default: src/cavalry-batch of this tree)
#   --bench PATH   cavalry_bench, for --relmse, and beside it plot and
#                  gen_scene (default: next to this script)
#   --scenes DIR   the shared scenes (default $CV_SHARED_SCENES, else
#                  ../shared/scenes of the tree, else shared/scenes in it)
#   --times T      wall-time limits in seconds (default "2 4 8")
#   --spp N        equal samples instead of equal time: every render takes N
#                  spp with no time limit (its limit column reads 0)
#   --seeds S      seeds of every render (default "1 2 3")
#   --size WxH     film size of every render (default: each scene's own)
#   --ref-spp N    samples per pixel of the path reference (default 8192;
#                  seed 1000, apart from the seeds compared)
#   --room-triangles N  triangles of the generated closed room (default 100k)
#   --variants V   what is compared: path; rlpath (the defaults); rlpath-online
#                  (rlpath.train: 0, Dahm and Keller's learning through the
#                  whole render); rlpath-frozen-N (rlpath.train: N);
#                  rlpath-sdtree (rlpath.method: sdtree, Müller et al.'s
#                  trees); rlpath-sdtree-N (the same trained over N spp)
#   --rl SETTINGS  more rlpath settings for every rlpath variant, a YAML flow
#                  mapping's inside ("mix: 0.5, grid: 8")
#   --work DIR     references, images, logs, results (default bench/out/guiding)
#   --summarize    render nothing: only the medians, table and plots of the
#                  renders in DIR/runs.csv (a run replaces the lines of the
#                  scenes it renders and keeps the others, so one scene per
#                  call, then --summarize, gives the table of all)
#   scenes         names (veach-ajar, veach-bidir, cornell-box, room: the
#                  generated closed room lit by bounced light) or .pbrt files;
#                  default: "veach-ajar veach-bidir cornell-box room"
# Writes DIR/runs.csv (scene,variant,limit,seed,spp,seconds,render_seconds,
# relmse: one line per render), DIR/medians.csv (per scene, variant and
# limit, the median over the seeds), DIR/table.md (medians, and each
# variant's relMSE over path's at the same limit) and DIR/NAME.png (relMSE
# against the time limit, log-log, one series per variant).
set -u
here=$(cd "$(dirname "$0")" && pwd)
srcdir=$(cd "$here/.." && pwd)
batch=$srcdir/src/cavalry-batch
benchbin=$here/cavalry_bench
shared=${CV_SHARED_SCENES:-}
times="2 4 8"
seeds="1 2 3"
size=
ref_spp=8192
room_tris=100k
variants="path rlpath rlpath-online"
rl_extra=
spp_only=
work=
scenes=
summarize_only=0
. "$here/common.sh"
usage() { bench_usage "$0"; }
while [ $# -gt 0 ]; do
    case "$1" in
    --batch) batch=$2; shift 2 ;;
    --bench) benchbin=$2; shift 2 ;;
    --scenes) shared=$2; shift 2 ;;
    --times) times=$2; shift 2 ;;
    --spp) spp_only=$2; times=0; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --room-triangles) room_tris=$2; shift 2 ;;
    --variants) variants=$2; shift 2 ;;
    --rl) rl_extra=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --summarize) summarize_only=1; shift ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "guiding.sh: unknown option $1" >&2; exit 2 ;;
    *) scenes="$scenes $1"; shift ;;
    esac
done
# own_train VARIANT: the rlpath.train a variant sets itself; nothing for
# one of the default training (or --rl's)
own_train() {
    case "$1" in
    rlpath-online) echo 0 ;;
    rlpath-frozen-*|rlpath-sdtree-*) echo "${1##*-}" ;;
    esac
}
# the training --rl sets; nothing where it sets none
rl_train=$(printf '%s' "$rl_extra" | sed -n 's/.*train: *\([0-9]*\).*/\1/p')
# a variant that sets its own training takes none from --rl (its manifest
# would name the key twice)
case "$rl_extra" in
*train:*)
    for v in $variants; do
        if [ -n "$(own_train "$v")" ]; then
            echo "guiding.sh: --rl sets train, which the variant $v sets itself" >&2
            exit 2
        fi
    done ;;
esac
for b in "$batch" "$benchbin"; do
    [ -x "$b" ] || { echo "guiding.sh: $b not found or not executable; build it or pass --batch/--bench" >&2; exit 2; }
done
bindir=$(cd "$(dirname "$benchbin")" && pwd)
if [ -z "$shared" ]; then
    shared=$srcdir/../shared/scenes
    [ -d "$shared" ] || shared=$srcdir/shared/scenes
fi
# absolute: the jobs' manifests are written in the work folder, and a
# scene path in them is read from there
[ -d "$shared" ] && shared=$(cd "$shared" && pwd)
[ -n "$scenes" ] || scenes="veach-ajar veach-bidir cornell-box room"
[ -n "$work" ] || work=$here/out/guiding
mkdir -p "$work/ref" "$work/img" "$work/logs" "$work/cache" || exit 1
work=$(cd "$work" && pwd)
# one program cache for every run, warmed before the timed renders
CAVALRY_CACHE_DIR=$work/cache
export CAVALRY_CACHE_DIR

# The .pbrt file of a scene name (or the file given).
scene_file() {
    case "$1" in
    *.pbrt) echo "$1" ;;
    room)
        d=$work/room-$room_tris
        if [ ! -f "$d/scene.pbrt" ]; then
            "$bindir/gen_scene" --triangles "$room_tris" --seed 1 --indirect --out "$d" >&2 ||
                return 1
        fi
        echo "$d/scene.pbrt" ;;
    *) echo "$shared/$1/scene-v4.pbrt" ;;
    esac
}

# The manifest lines of a variant's integrator. With warm=1 (the warm-up
# job) a variant of the default training trains over 1 spp instead: the
# same programs, and a job of 2 spp then also builds those of the passes
# after training, which a job within its training does not ask for.
warm=0
variant_yaml() {
    extra=${rl_extra:+, $rl_extra}
    # the settings of a variant of the default training: for its warm-up,
    # training over 1 spp (unless --rl sets a training: its warm-up runs one
    # spp past that one, below)
    dflt=$extra
    case "$warm,$rl_extra" in
    0,*|1,*train:*) ;;
    *) dflt="$extra, train: 1" ;;
    esac
    case "$1" in
    path) printf '    integrator: path\n' ;;
    rlpath) printf '    integrator: rlpath\n'
        [ -z "$dflt" ] || printf '    rlpath: {%s}\n' "${dflt#, }" ;;
    rlpath-online|rlpath-frozen-*) printf '    integrator: rlpath\n    rlpath: {train: %s%s}\n' "$(own_train "$1")" "$extra" ;;
    rlpath-sdtree) printf '    integrator: rlpath\n    rlpath: {method: sdtree%s}\n' "$dflt" ;;
    rlpath-sdtree-*) printf '    integrator: rlpath\n    rlpath: {method: sdtree, train: %s%s}\n' "$(own_train "$1")" "$extra" ;;
    *) echo "guiding.sh: unknown variant $1" >&2; return 1 ;;
    esac
}

# render NAME SCENE VARIANT SEED SPP LIMIT: one cavalry-batch job writing
# $work/img/NAME.exr; prints "spp seconds render_seconds" from its report.
render() {
    m=$work/logs/$1.yaml
    {
        printf 'version: 1\njobs:\n  - name: %s\n    scene: %s\n' "$1" "$2"
        variant_yaml "$3" || return 1
        printf '    seed: %s\n    spp: %s\n    formats: [exr]\n    exr: {half: false}\n' "$4" "$5"
        [ -z "$size" ] || printf '    resolution: %s\n' "$size"
    } > "$m" || return 1
    rm -f "$work/img/$1.exr"
    lim=
    [ "$6" = 0 ] || lim=--time-limit=$6
    # shellcheck disable=SC2086
    "$batch" --progress=json --output-dir="$work/img" --force $lim "$m" > "$work/logs/$1.json" \
        2> "$work/logs/$1.err"
    if [ ! -f "$work/img/$1.exr" ]; then
        echo "guiding.sh: $1 made no image (see $work/logs/$1.err)" >&2
        return 1
    fi
    awk '/"event":"job_(finished|partial)"/ {
        spp = $0; sub(/.*"spp":/, "", spp); sub(/[,}].*/, "", spp)
        s = $0; sub(/.*"seconds":/, "", s); sub(/[,}].*/, "", s)
        r = $0; sub(/.*"render_seconds":/, "", r); sub(/[,}].*/, "", r)
        print spp, s, r; found = 1 }
        END { if (!found) print "0 0 0" }' "$work/logs/$1.json"
}

# runs.csv keeps the renders of scenes not run this time (one scene per
# call keeps each call short), and loses those of the scenes run now
runs=$work/runs.csv
header="scene,variant,limit,seed,spp,seconds,render_seconds,relmse"
if [ "$summarize_only" = 0 ]; then
    names=
    for s in $scenes; do names="$names $(basename "$s" .pbrt)"; done
    if [ -f "$runs" ]; then
        awk -F, -v names="$names" 'BEGIN { n = split(names, a, " "); for (i = 1; i <= n; i++) drop[a[i]] = 1 }
            NR == 1 || !($1 in drop)' "$runs" > "$runs.tmp" && mv "$runs.tmp" "$runs"
    else
        echo "$header" > "$runs"
    fi
fi
[ -f "$runs" ] || { echo "guiding.sh: no $runs to summarize" >&2; exit 1; }
[ "$summarize_only" = 1 ] && scenes=
for s in $scenes; do
    file=$(scene_file "$s") || { echo "guiding.sh: cannot make scene $s" >&2; exit 1; }
    [ -f "$file" ] || { echo "guiding.sh: $file not found, $s skipped" >&2; continue; }
    name=$(basename "$s" .pbrt)
    ref=$work/ref/$name-${size:-own}-$ref_spp.exr
    if [ ! -f "$ref" ]; then
        echo "guiding.sh: $name: reference, path at $ref_spp spp" >&2
        render "ref-$name" "$file" path 1000 "$ref_spp" 0 > /dev/null || exit 1
        mv "$work/img/ref-$name.exr" "$ref" || exit 1
    fi
    # warm the program cache: no timed render compiles (those of the
    # passes after training too: a variant of its own training warms up
    # past it)
    for v in $variants; do
        # past its own training, else past --rl's or the warm-up's 1 spp
        own=$(own_train "$v")
        wspp=$((${rl_train:-1} + 1))
        [ "${own:-0}" -eq 0 ] || wspp=$((own + 1))
        warm=1
        render "warm-$name-$v" "$file" "$v" 1 "$wspp" 0 > /dev/null || exit 1
        warm=0
    done
    for t in $times; do
        for seed in $seeds; do
            for v in $variants; do
                id=$name-$v-$t-s$seed
                r=$(render "$id" "$file" "$v" "$seed" "${spp_only:-1000000}" "$t") || exit 1
                e=$("$benchbin" --relmse "$work/img/$id.exr" "$ref" | awk '{ print $1 }')
                set -- $r
                echo "$name,$v,$t,$seed,$1,$2,$3,$e" >> "$runs"
                echo "guiding.sh: $id: $1 spp, $2 s, relMSE $e" >&2
            done
        done
    done
done

# medians over the seeds (a firefly in one render decides nothing)
awk -F, 'NR > 1 {
    k = $1 "," $2 "," $3; if (!(k in n)) order[++nk] = k
    i = ++n[k]; spp[k, i] = $5; sec[k, i] = $6; err[k, i] = $8 }
function med(a, k, c,   i, j, x, v) {
    for (i = 1; i <= c; i++) v[i] = a[k, i] + 0
    for (i = 2; i <= c; i++) { x = v[i]; for (j = i - 1; j >= 1 && v[j] > x; j--) v[j + 1] = v[j]; v[j + 1] = x }
    return (c % 2) ? v[(c + 1) / 2] : (v[c / 2] + v[c / 2 + 1]) / 2 }
END {
    print "scene,variant,limit,seeds,spp,seconds,relmse"
    for (q = 1; q <= nk; q++) { k = order[q]
        printf "%s,%d,%g,%g,%.6g\n", k, n[k], med(spp, k, n[k]), med(sec, k, n[k]), med(err, k, n[k]) }
}' "$runs" > "$work/medians.csv" || exit 1

# the table: each variant against path at the same limit
awk -F, 'NR > 1 { k = $1 "," $3; e[k, $2] = $7; s[k, $2] = $5
    if (!(k in seen)) { seen[k] = 1; rows[++nr] = k }
    if (!($2 in vs)) { vs[$2] = 1; vl[++nv] = $2 } }
END {
    printf "| scene | limit (s) |"; for (i = 1; i <= nv; i++) printf " %s relMSE (spp) |", vl[i]
    for (i = 1; i <= nv; i++) if (vl[i] != "path") printf " %s / path |", vl[i]
    printf "\n| --- | --- |"; for (i = 1; i <= nv; i++) printf " --- |"
    for (i = 1; i <= nv; i++) if (vl[i] != "path") printf " --- |"
    printf "\n"
    for (r = 1; r <= nr; r++) { k = rows[r]; split(k, p, ",")
        printf "| %s | %s |", p[1], p[2]
        # a variant not run on this scene reads "-"
        for (i = 1; i <= nv; i++)
            printf " %s |", ((k, vl[i]) in e) ? sprintf("%.4g (%d)", e[k, vl[i]], s[k, vl[i]]) : "-"
        for (i = 1; i <= nv; i++) if (vl[i] != "path")
            printf " %s |", (e[k, "path"] > 0 && (k, vl[i]) in e ? sprintf("%.2f", e[k, vl[i]] / e[k, "path"]) : "-")
        printf "\n" }
}' "$work/medians.csv" > "$work/table.md" || exit 1
cat "$work/table.md"

# one log-log plot per scene: relMSE against the time limit (the measured
# job seconds, in medians.csv, overshoot it by the last pass and the write)
for name in $(awk -F, 'NR > 1 { if (!($1 in s)) { s[$1] = 1; print $1 } }' "$work/medians.csv"); do
    args=
    for v in $variants; do
        c=$work/logs/plot-$name-$v.csv
        awk -F, -v n="$name" -v v="$v" 'NR == 1 { print "seconds,relmse" }
            NR > 1 && $1 == n && $2 == v { print $3 "," $7 }' "$work/medians.csv" > "$c"
        # no series for a variant not run on this scene
        [ "$(wc -l < "$c")" -gt 1 ] && args="$args $c=$v"
    done
    # shellcheck disable=SC2086
    "$bindir/plot" --out "$work/$name.png" --title "$name: relMSE at equal wall time" \
        --x seconds --y relmse --xlabel "wall-time limit (s)" --ylabel "relMSE (median over seeds)" \
        $args || exit 1
    echo "guiding.sh: wrote $work/$name.png" >&2
done
