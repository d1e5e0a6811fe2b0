#!/bin/sh
# converge.sh: error against render time for one or more renders of the same
# view (e.g. the path and rlpath integrators), as CSV per series and one
# log-log plot (PNG, drawn by bench/plot), the way integrators are compared.
#
# usage: bench/converge.sh [--binary PATH] [--reference REF.exr | --ref-spp N]
#                          [--spp N] [--width W --height H] [--out DIR]
#                          [--title T] LABEL=SCENE.pbrt...
#   Each LABEL=SCENE is one series: relMSE at 1, 2, 4, ... up to --spp
#   (default 1024) samples per pixel against --reference, or against a
#   render of that scene at --ref-spp (default 4096) when none is given.
#   Writes DIR/LABEL.csv (spp,seconds,gpu_seconds,relmse) and
#   DIR/convergence.png (relMSE vs GPU seconds). Default DIR: bench/out/converge.
set -u
here=$(cd "$(dirname "$0")" && pwd)
binary=
ref_args=
spp=1024
size_args=
out=
title="relMSE vs render time"
series=
while [ $# -gt 0 ]; do
    case "$1" in
    --binary) binary=$2; shift 2 ;;
    --reference) ref_args="--reference $2"; shift 2 ;;
    --ref-spp) ref_args="--ref-spp $2"; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --width|--height) size_args="$size_args $1 $2"; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --title) title=$2; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "converge.sh: unknown option $1" >&2; exit 2 ;;
    *=*) series="$series $1"; shift ;;
    *) echo "converge.sh: series must be LABEL=SCENE.pbrt, got $1" >&2; exit 2 ;;
    esac
done
[ -n "$binary" ] || for b in "$here/cavalry_bench" ./bench/cavalry_bench; do
    [ -x "$b" ] && { binary=$b; break; }
done
if [ -z "$binary" ] || [ ! -x "$binary" ]; then
    echo "converge.sh: cavalry_bench not found; build it or pass --binary" >&2
    exit 2
fi
plot="$(cd "$(dirname "$binary")" && pwd)/plot"
[ -n "$series" ] || { sed -n '5,10p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ -n "$out" ] || out="$(dirname "$binary")/out/converge"
mkdir -p "$out" || exit 1
csvs=
for s in $series; do
    label=${s%%=*}
    scene=${s#*=}
    echo "converge.sh: $label: $scene" >&2
    # shellcheck disable=SC2086
    "$binary" --converge "$scene" $ref_args --spp "$spp" $size_args --csv "$out/$label.csv" ||
        exit 1
    csvs="$csvs $out/$label.csv=$label"
done
# shellcheck disable=SC2086
"$plot" --out "$out/convergence.png" --title "$title" --x gpu_seconds --y relmse \
    --xlabel "GPU time (s)" --ylabel "relMSE" $csvs || exit 1
echo "converge.sh: wrote $out/convergence.png" >&2
