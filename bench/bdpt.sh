#!/bin/sh
# bdpt.sh: the bdpt integrator against path (or volpath, --against) at
# equal render time, on scenes with caustics: per scene a converged
# reference (bdpt at --ref-spp, rendered with cavalry-batch to EXR), then
# bench/converge.sh's series of relMSE against render time for the two,
# both against that reference (CSV and a plot per scene). A bdpt sample
# costs several path samples, so path's series runs to more samples
# (--path-spp), for the two to span the same render times.
#
# usage: bench/bdpt.sh [--ref-spp N] [--spp N] [--path-spp N] [--size WxH]
#                      [--against path|volpath] [--out DIR] SCENE.pbrt...
#   --ref-spp N  the reference's samples per pixel (default 4096)
#   --spp N      bdpt's series runs to N spp at doubling counts (default 256)
#   --path-spp N path's series runs to N spp (default 32 times --spp)
#   --size WxH   film size (default: the scene's)
#   --against I  the unidirectional integrator bdpt runs against: path
#                (default), or volpath for scenes with participating media
#   --out DIR    default bench/out/bdpt: DIR/NAME/{ref.exr,I.csv,
#                bdpt.csv,convergence.png}, NAME the scene file's name
# e.g. bench/bdpt.sh ../shared/scenes/veach-bidir/scene-v4.pbrt \
#          ../shared/scenes/caustic-glass/caustic-glass-v4.pbrt
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
ref_spp=4096
spp=256
path_spp=
size=
out=
against=path
scenes=
while [ $# -gt 0 ]; do
    case "$1" in
    --ref-spp) ref_spp=$2; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --path-spp) path_spp=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --against)
        case "$2" in path|volpath) against=$2 ;;
        *) echo "bdpt.sh: --against takes path or volpath, not $2" >&2; exit 2 ;;
        esac
        shift 2 ;;
    -h|--help) bench_usage "$0"; exit 0 ;;
    -*) echo "bdpt.sh: unknown option $1" >&2; exit 2 ;;
    *) scenes="$scenes $1"; shift ;;
    esac
done
[ -n "$scenes" ] || { bench_usage "$0" >&2; exit 2; }
batch=$(bench_binary bdpt.sh "" "$here/../src/cavalry-batch" ./src/cavalry-batch) || exit 2
batch=$(cd "$(dirname "$batch")" && pwd)/cavalry-batch
[ -n "$out" ] || out="$here/out/bdpt"
[ -n "$path_spp" ] || path_spp=$((32 * spp))
plot=
for p in "$here/plot" ./bench/plot; do
    [ -x "$p" ] && { plot=$p; break; }
done
[ -n "$plot" ] || { echo "bdpt.sh: bench/plot not found; build it" >&2; exit 2; }
size_key=
size_args=
if [ -n "$size" ]; then
    size_key=", resolution: [${size%x*}, ${size#*x}]"
    size_args="--width ${size%x*} --height ${size#*x}"
fi
for scene in $scenes; do
    scene=$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")
    name=$(basename "$scene" .pbrt)
    dir="$out/$name"
    mkdir -p "$dir" || exit 1
    {
        echo 'version: 1'
        echo 'jobs:'
        echo "  - {name: ref, scene: \"$scene\", integrator: bdpt, spp: $ref_spp,"
        echo "     output: \"$dir/ref\", formats: [exr], seed: 7$size_key}"
    } >"$dir/ref.yaml"
    echo "bdpt.sh: $name: reference, bdpt at $ref_spp spp" >&2
    "$batch" --force "$dir/ref.yaml" >"$dir/ref.log" 2>&1 ||
        { echo "bdpt.sh: the reference failed; see $dir/ref.log" >&2; exit 1; }
    # one series at a time, each to its own sample count, then one plot
    # shellcheck disable=SC2086
    "$here/converge.sh" --reference "$dir/ref.exr" --spp "$path_spp" $size_args --out "$dir" \
        "$against=$scene@$against" || exit 1
    # shellcheck disable=SC2086
    "$here/converge.sh" --reference "$dir/ref.exr" --spp "$spp" $size_args --out "$dir" \
        "bdpt=$scene@bdpt" || exit 1
    "$plot" --out "$dir/convergence.png" --title "$name: relMSE vs render time" --x seconds \
        --y relmse --xlabel "render time (s)" --ylabel "relMSE" "$dir/$against.csv=$against" \
        "$dir/bdpt.csv=bdpt" || exit 1
    echo "bdpt.sh: wrote $dir/convergence.png" >&2
done
