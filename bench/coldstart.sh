#!/bin/sh
# coldstart.sh: time from process start to the first finished pass on an
# empty program cache (issue 26: at most 2 s for any scene), and where the
# cold seconds go. Every run is a fresh process of cavalry_bench with an
# empty Cavalry cache folder (CAVALRY_CACHE_DIR) and the drivers' own shader
# caches off (__GL_SHADER_DISK_CACHE=0 for NVIDIA, MESA_SHADER_CACHE_DISABLE
# for Mesa), so nothing compiled by an earlier run is reused.
#
# usage: bench/coldstart.sh [--binary PATH] [--repeat K] [--spp N]
#                           [--size WxH] [--modes "parallel serial warm"]
#                           [--integrator path|rlpath|rlpath-sdtree]
#                           [--work DIR]
#                           [--out FILE] [scenes...]
#   --binary PATH  cavalry_bench (default: next to this script, then
#                  ./bench/cavalry_bench); an older build's (a baseline)
#                  gives the time to the first pass without program.* keys
#   --repeat K     runs per scene and mode (default 5); medians are printed
#   --spp N        samples per pixel of the render (default 1: the first
#                  pass is what is timed)
#   --size WxH     film size (default: the scene's own)
#   --modes M      any of: parallel (programs compiled ahead in the
#                  driver's threads, the default behaviour), serial
#                  (CAVALRY_PARALLEL_COMPILE=0: one program at a time at
#                  first use, which times each program's own compile), warm
#                  (a second run on the cache folder the cold run filled).
#                  Default: "parallel serial warm".
#   --integrator I path (default), rlpath, or rlpath-sdtree (rlpath with
#                  rlpath.method: sdtree, as bench/guiding.sh names it)
#   --work DIR     records, logs and summaries (default bench/out/coldstart)
#   scenes         .pbrt files (default: cornell-box, coffee, veach-ajar and
#                  killeroo-coated-gold from ../shared/scenes where present)
# Prints, per scene and mode, the medians of render.first_pass_from_start_ms,
# program.build_ms, program.wait_ms, program.compiled and program.cache_hits,
# then per scene the costliest programs of the serial runs (median of
# compile + link ms over the runs, from the -v log) and the last programs
# the parallel runs first used (when each was requested and first used,
# and the wait there: the order in which the driver finished them). Writes
# DIR/<mode>.jsonl (records), DIR/<mode>-summary.json (cavalry_bench
# --summarize), DIR/logs/ and DIR/table.txt.
set -u

here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
srcdir=$(cd "$here/.." && pwd)
binary=
repeat=5
spp=1
size=
modes="parallel serial warm"
integrator=path
work=
out=
scenes=

while [ $# -gt 0 ]; do
    case "$1" in
    --binary) binary=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --modes) modes=$2; shift 2 ;;
    --integrator) integrator=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) bench_usage "$0"; exit 0 ;;
    -*) echo "coldstart.sh: unknown option $1" >&2; exit 2 ;;
    *) scenes="$scenes $1"; shift ;;
    esac
done

binary=$(bench_binary coldstart.sh "$binary" "$here/cavalry_bench" "./bench/cavalry_bench") || exit 2
[ -n "$work" ] || work="$(cd "$(dirname "$binary")" && pwd)/out/coldstart"
mkdir -p "$work/logs" || exit 1
if [ -z "$scenes" ]; then
    shared=${CV_SHARED_SCENES:-$srcdir/../shared/scenes}
    for s in cornell-box/scene-v4.pbrt coffee/scene-v4.pbrt veach-ajar/scene-v4.pbrt \
             killeroos/killeroo-coated-gold.pbrt; do
        if [ -f "$shared/$s" ]; then
            scenes="$scenes $shared/$s"
        else
            echo "coldstart.sh: $shared/$s not found, skipped" >&2
        fi
    done
fi
# An older cavalry_bench (before the program log, e.g. f42fcef for a
# baseline) takes no -v: its records lack program.* and the costliest list.
verbose=
"$binary" --help 2>/dev/null | grep -q -- '\[-v\]' && verbose=-v
case "$integrator" in
rlpath-sdtree) size_args="--integrator rlpath --rl-method sdtree" ;;
*) size_args="--integrator $integrator" ;;
esac
[ -z "$size" ] || size_args="$size_args --width ${size%x*} --height ${size#*x}"

# The drivers' own caches stay off in every mode: only Cavalry's folder
# differs between cold and warm.
__GL_SHADER_DISK_CACHE=0
MESA_SHADER_CACHE_DISABLE=true
export __GL_SHADER_DISK_CACHE MESA_SHADER_CACHE_DISABLE

tmp=$(mktemp -d "${TMPDIR:-/tmp}/cv_coldstart_XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM

# tag MODE SCENE: the start of the names of MODE's logs of SCENE
tag() { echo "$work/logs/$1-$(basename "$(dirname "$2")")-$(basename "$2" .pbrt)"; }
# name SCENE: the scene as the table names it
name() { echo "$(basename "$(dirname "$1")")/$(basename "$1")"; }

# run MODE SCENE K CACHE_DIR: one process, its record appended to MODE.jsonl
run() {
    log="$(tag "$1" "$2")-$3.log"
    par=1
    [ "$1" != serial ] || par=0
    # shellcheck disable=SC2086
    CAVALRY_CACHE_DIR=$4 CAVALRY_PARALLEL_COMPILE=$par \
        "$binary" $verbose --bench "$2" --spp "$spp" $size_args --repeat 1 --json \
        >> "$work/$1.jsonl" 2> "$log" ||
        echo "coldstart.sh: $1 run of $2 failed: $(tail -n 1 "$log")" >&2
}

for m in $modes; do
    : > "$work/$m.jsonl"
done
for s in $scenes; do
    k=0
    while [ "$k" -lt "$repeat" ]; do
        for m in $modes; do
            case "$m" in
            parallel|serial)
                c="$tmp/cache-$m-$k"
                rm -rf "$c"
                echo "coldstart.sh: $s $m (run $((k + 1))/$repeat)" >&2
                run "$m" "$s" "$k" "$c"
                ;;
            warm)
                # the folder a cold run filled; a run of its own fills one
                c="$tmp/cache-warm-$k"
                rm -rf "$c"
                CAVALRY_CACHE_DIR=$c "$binary" --bench "$s" --spp 1 $size_args --repeat 1 \
                    > /dev/null 2>&1
                echo "coldstart.sh: $s warm (run $((k + 1))/$repeat)" >&2
                run warm "$s" "$k" "$c"
                ;;
            *) echo "coldstart.sh: unknown mode $m" >&2; exit 2 ;;
            esac
        done
        k=$((k + 1))
    done
done

# awk's med(LIST): the median of the space-separated numbers in LIST (the
# lower of the middle two for an even count, as median below)
awk_med='function med(list,   a, n, i, j, t) {
    n = split(list, a, " ")
    for (i = 2; i <= n; i++)
        for (j = i; j > 1 && a[j - 1] + 0 > a[j] + 0; j--) {
            t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
    return a[int((n + 1) / 2)] }'

# median of the numbers on standard input
median() {
    sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) { print "-"; exit }
        print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
# key FILE SCENE KEY: the key's values in FILE's records of SCENE
key() {
    grep -F "\"scene\": \"$2\"" "$1" | sed -n "s/.*\"$3\": \([-0-9.e+]*\).*/\1/p"
}

table="$work/table.txt"
{
    printf '%-40s %-9s %9s %9s %9s %8s %6s\n' scene mode first_ms build_ms wait_ms compiled hits
    for s in $scenes; do
        for m in $modes; do
            f="$work/$m.jsonl"
            printf '%-40s %-9s %9s %9s %9s %8s %6s\n' "$(name "$s")" "$m" \
                "$(key "$f" "$s" render.first_pass_from_start_ms | median)" \
                "$(key "$f" "$s" program.build_ms | median)" \
                "$(key "$f" "$s" program.wait_ms | median)" \
                "$(key "$f" "$s" program.compiled | median)" \
                "$(key "$f" "$s" program.cache_hits | median)"
        done
    done
    case " $modes " in
    *" serial "*)
        for s in $scenes; do
            echo
            echo "$(name "$s"): costliest programs, serial runs (median compile + link ms)"
            # "program glsl/P [D]: compiled: ..., compile C ms, link L ms, ..."
            cat "$(tag serial "$s")"-*.log 2>/dev/null |
                sed -n 's/.*program glsl\/\(.*\): compiled: .*, compile \([0-9.]*\) ms, link \([0-9.]*\) ms,.*/\2 \3 \1/p' |
                awk "$awk_med"'
                     { p = $0; sub(/^[^ ]* [^ ]* /, "", p); v[p] = v[p] " " ($1 + $2) }
                     END { for (p in v) printf "%10.1f  %s\n", med(v[p]), p }' |
                sort -rg | head -n 12
        done
        ;;
    esac
    case " $modes " in
    *" parallel "*)
        for s in $scenes; do
            echo
            echo "$(name "$s"): the last programs the parallel runs first used" \
                "(median ms after the context was made: requested, used; wait there)"
            # "...: compiled: ..., wait W ms, ...; first used ... (requested at R ms, first
            # used at U ms of the context)"
            cat "$(tag parallel "$s")"-*.log 2>/dev/null |
                sed -n 's/.*program glsl\/\(.*\): compiled: .*, wait \([0-9.]*\) ms, .*(requested at \([0-9]*\) ms, first used at \([0-9]*\) ms of the context)/\3 \4 \2 \1/p' |
                awk "$awk_med"'
                     { p = $0; sub(/^[^ ]* [^ ]* [^ ]* /, "", p)
                       r[p] = r[p] " " $1; u[p] = u[p] " " $2; w[p] = w[p] " " $3 }
                     END { for (p in u) printf "%8d %8d %9.1f  %s\n", med(r[p]), med(u[p]), med(w[p]), p }' |
                sort -k2,2g | tail -n 12
        done
        ;;
    esac
} > "$table"
for m in $modes; do
    "$binary" --summarize "$work/$m.jsonl" --out "$work/$m-summary.json" 2> /dev/null ||
        echo "coldstart.sh: no summary for $m" >&2
done
cat "$table"
[ -z "$out" ] || cp "$table" "$out" || exit 1
