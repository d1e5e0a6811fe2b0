#!/bin/sh
# converge.sh: error against render time for one or more renders of the same
# view (e.g. the path and rlpath integrators), as CSV per series and one
# log-log plot (PNG, drawn by bench/plot), the way integrators are compared.
#
# usage: bench/converge.sh [--binary PATH] [--reference REF.exr | --ref-spp N]
#                          [--spp N] [--width W --height H] [--out DIR]
#                          [--integrator path|rlpath|volpath|bdpt]
#                          [--title T] LABEL=SCENE.pbrt[@INTEGRATOR]...
#   Each LABEL=SCENE is one series (@path or @rlpath picks its integrator,
#   e.g. path=room.pbrt@path rlpath=room.pbrt@rlpath): relMSE at 1, 2, 4, ... up to --spp
#   (default 1024) samples per pixel against --reference, or against a
#   render of that scene at --ref-spp (default 4096) when none is given.
#   Writes DIR/LABEL.csv (spp,seconds,wall_seconds,gpu_seconds,relmse;
#   seconds = GPU time, wall time on llvmpipe) and DIR/convergence.png
#   (relMSE vs seconds). Default DIR: bench/out/converge.
set -u
here=$(cd "$(dirname "$0")" && pwd)
binary=
ref_args=
spp=1024
size_args=
integ=
out=
title="relMSE vs render time"
series=
while [ $# -gt 0 ]; do
    case "$1" in
    --binary) binary=$2; shift 2 ;;
    --reference) ref_args="--reference $2"; shift 2 ;;
    --ref-spp) ref_args="--ref-spp $2"; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --integrator) integ="--integrator $2"; shift 2 ;;
    --width|--height) size_args="$size_args $1 $2"; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --title) title=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
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
[ -n "$series" ] || { awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0" >&2; exit 2; }
[ -n "$out" ] || out="$(dirname "$binary")/out/converge"
mkdir -p "$out" || exit 1
csvs=
for s in $series; do
    label=${s%%=*}
    scene=${s#*=}
    this_integ=$integ
    case "$scene" in
    *@*) this_integ="--integrator ${scene##*@}"; scene=${scene%@*} ;;
    esac
    echo "converge.sh: $label: $scene $this_integ" >&2
    # shellcheck disable=SC2086
    "$binary" --converge "$scene" $ref_args --spp "$spp" $size_args $this_integ --csv "$out/$label.csv" ||
        exit 1
    csvs="$csvs $out/$label.csv=$label"
done
# shellcheck disable=SC2086
"$plot" --out "$out/convergence.png" --title "$title" --x seconds --y relmse \
    --xlabel "render time (s)" --ylabel "relMSE" $csvs || exit 1
echo "converge.sh: wrote $out/convergence.png" >&2
