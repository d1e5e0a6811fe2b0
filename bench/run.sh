#!/bin/sh
# run.sh: runs Cavalry's fixed benchmark set and prints one JSON document
# (stdout, and --out FILE) and a short table (stderr). Every repeat is a fresh
# process of cavalry_bench, so load time and time to the first pass count
# from process start; the summary gives median, min, max and spread.
#
# usage: bench/run.sh [--binary PATH] [--quick] [--repeat K] [--spp N]
#                     [--size WxH] [--sizes "1M 4M"] [--timeout SEC]
#                     [--out results.json] [--work DIR] [--save] [scenes...]
#   --binary PATH  cavalry_bench to run (default: next to this script, then
#                  ./bench/cavalry_bench of the build tree); gen_scene is
#                  taken from the same folder.
#   --quick        small generated scenes (100k, 300k, 100k indirect, 100k
#                  production), 160x90, 2 spp, 300 s per run at most: minutes
#                  on llvmpipe. Default (full): 1M, 4M, 16M, 1M indirect and
#                  1M and 4M production at 1280x720, 64 spp.
#   --sizes, --size, --spp, --repeat (3), --timeout: override those.
#   --save         also write bench/results/YYYY-MM-DD_<gpu>_<commit>.json
#                  (done by default for full runs on a hardware GPU).
#   scenes         .pbrt files to run instead of the fixed set.
# Generated scenes are cached under --work (default bench/out/scenes). Every
# run also writes --work/RESULTS-entry.md: a bench/RESULTS.md section with
# the commit, GPU, median table and command, to complete and paste there.
set -u

cmdline="bench/run.sh $*"
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
srcdir=$(cd "$here/.." && pwd)
binary=
quick=no
repeat=3
spp=
out=
work=
save=auto
scenes=
size=
sizes=
limit=

while [ $# -gt 0 ]; do
    case "$1" in
    --binary) binary=$2; shift 2 ;;
    --quick) quick=yes; shift ;;
    --repeat) repeat=$2; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --save) save=yes; shift ;;
    --no-save) save=no; shift ;;
    --size) size=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --timeout) limit=$2; shift 2 ;;
    -h|--help) bench_usage "$0"; exit 0 ;;
    -*) echo "run.sh: unknown option $1" >&2; exit 2 ;;
    *) scenes="$scenes $1"; shift ;;
    esac
done

binary=$(bench_binary run.sh "$binary" "$here/cavalry_bench" "./bench/cavalry_bench") || exit 2
bindir=$(cd "$(dirname "$binary")" && pwd)
gen="$bindir/gen_scene"
[ -n "$work" ] || work="$bindir/out"
mkdir -p "$work/scenes" || exit 1

if [ "$quick" = yes ]; then
    [ -n "$sizes" ] || sizes="100k 300k"
    indirect="100k"
    production="100k"
    [ -n "$size" ] || size=160x90
    [ -n "$spp" ] || spp=2
    [ -n "$limit" ] || limit=300
else
    [ -n "$sizes" ] || sizes="1M 4M 16M"
    indirect="1M"
    production="1M 4M"
    [ -n "$size" ] || size=1280x720
    [ -n "$spp" ] || spp=64
fi
size_args="--width ${size%x*} --height ${size#*x}"
# A run that outlives --timeout is recorded as such and the set goes on.
runner=
if [ -n "$limit" ] && command -v timeout >/dev/null 2>&1; then
    runner="timeout $limit"
fi

# The fixed set: generated scenes, then the shared pbrt scenes where present.
if [ -z "$scenes" ]; then
    if [ ! -x "$gen" ]; then
        echo "run.sh: $gen not found (build the tree first)" >&2
        exit 2
    fi
    for n in $sizes; do
        d="$work/scenes/gen-$n-seed1"
        if [ ! -f "$d/scene.pbrt" ]; then
            "$gen" --triangles "$n" --seed 1 --out "$d" || exit 1
        fi
        scenes="$scenes $d/scene.pbrt"
    done
    for n in $indirect; do
        d="$work/scenes/gen-$n-indirect-seed1"
        if [ ! -f "$d/scene.pbrt" ]; then
            "$gen" --triangles "$n" --seed 1 --indirect --out "$d" || exit 1
        fi
        scenes="$scenes $d/scene.pbrt"
    done
    # Production look: 64 materials, coated plastics and conductors, image
    # textures of several sizes (what real scenes spend their shading on).
    for n in $production; do
        d="$work/scenes/gen-$n-production-seed1"
        if [ ! -f "$d/scene.pbrt" ]; then
            "$gen" --triangles "$n" --seed 1 --production --out "$d" || exit 1
        fi
        scenes="$scenes $d/scene.pbrt"
    done
    shared=${CV_SHARED_SCENES:-$srcdir/../shared/scenes}
    for s in cornell-box/scene-v4.pbrt veach-bidir/scene-v4.pbrt killeroos/killeroo-simple.pbrt; do
        if [ -f "$shared/$s" ]; then
            scenes="$scenes $shared/$s"
        else
            echo "run.sh: $shared/$s not found, skipped" >&2
        fi
    done
fi

records="$work/records.jsonl"
: > "$records"
json_escape() {
    printf '%s' "$1" | sed 's/\\/\\\\/g; s/"/\\"/g' | tr -d '\n\r'
}
for s in $scenes; do
    k=0
    while [ "$k" -lt "$repeat" ]; do
        echo "run.sh: $s (repeat $((k + 1))/$repeat)" >&2
        # shellcheck disable=SC2086
        $runner "$binary" --bench "$s" --spp "$spp" $size_args --repeat 1 --json \
            >> "$records" 2> "$work/stderr.txt"
        rc=$?
        if [ $rc -ne 0 ]; then
            msg=$(tail -n 1 "$work/stderr.txt")
            [ $rc -ne 124 ] || msg="timed out after $limit s (--timeout)"
            echo "run.sh: $s failed (exit $rc): $msg" >&2
            printf '{"scene": "%s", "repeat": %d, "unavailable.run": "exit %d: %s"}\n' \
                "$(json_escape "$s")" "$k" "$rc" "$(json_escape "$msg")" >> "$records"
            break
        fi
        k=$((k + 1))
    done
done

summary="$work/summary.json"
"$binary" --summarize "$records" --out "$summary" 2> "$work/table.txt" ||
    { cat "$work/table.txt" >&2; exit 1; }
cat "$summary"
cat "$work/table.txt" >&2
[ -z "$out" ] || cp "$summary" "$out" || exit 1

# Keep the summary of a hardware GPU run in the repository, named by date,
# GPU and commit, and describe it in bench/RESULTS.md: one JSON per result,
# not the records or logs.
field() {
    sed -n "s/.*\"gpu\": {.*\"$1\": \"\([^\"]*\)\".*/\1/p" "$summary" | head -n 1
}
renderer=$(field renderer)
version=$(field version)
# The driver is what follows the GL version: "4.6.0 NVIDIA 550.54.14".
driver=$(printf '%s' "$version" | sed 's/^[0-9.]* *//; s/(Core Profile) *//')
commit=$(git -C "$srcdir" rev-parse --short HEAD 2>/dev/null) || commit=unknown
if [ "$commit" != unknown ] && [ -n "$(git -C "$srcdir" status --porcelain --untracked-files=no 2>/dev/null)" ]; then
    commit="$commit-dirty"
fi
slug() { printf '%s' "$1" | tr -cs 'A-Za-z0-9.' '-' | sed 's/^-//; s/-$//'; }
name="$(date -u +%Y-%m-%d)_$(slug "${renderer:-unknown}")_$(slug "$commit").json"
entry="$work/RESULTS-entry.md"
{
    echo "### TITLE: what was measured"
    echo
    echo "\`bench/results/$name\` (if saved), main at $commit, ${renderer:-unknown GPU},"
    echo "driver ${driver:-unknown}, $(date -u +%Y-%m-%d)."
    echo
    echo "- **Question.** ..."
    echo "- **Answer.** Medians over $repeat repeats per scene, one process each:"
    echo
    sed 's/^/      /' "$work/table.txt"
    echo
    echo "- **Decision.** ..."
    echo "- **Reproduce.** \`$cmdline\`"
} > "$entry"
echo "run.sh: wrote $entry (a section for bench/RESULTS.md)" >&2
if [ "$save" = auto ]; then
    save=no
    case "$renderer" in
    *llvmpipe*|*softpipe*|*Software*|"") ;;
    *) [ "$quick" = no ] && save=yes ;;
    esac
fi
if [ "$save" = yes ]; then
    mkdir -p "$srcdir/bench/results" && cp "$summary" "$srcdir/bench/results/$name" &&
        echo "run.sh: saved bench/results/$name" >&2
fi
exit 0
