#!/bin/sh
# multigpu.sh: the speed-up of a multi-GPU batch. Renders one manifest of N
# jobs (one scene, a seed each) with cavalry-batch --gpu 0, then with
# --gpu all (or --gpus SPEC), and prints both wall times, the speed-up and
# how many jobs each worker rendered. A warm-up job first fills the program
# cache, so neither timed run pays for compiling the shaders; each timed run
# is a fresh process that loads the scene itself, as a farm task would.
#
# usage: bench/multigpu.sh [--binary PATH] [--jobs N] [--spp S] [--size WxH]
#                          [--triangles T] [--gpus SPEC] [--repeat K]
#                          [--work DIR] [scene.pbrt]
#   --binary PATH  cavalry-batch to run (default: ../src/cavalry-batch from
#                  this script, then ./src/cavalry-batch)
#   --jobs N       jobs in the manifest (default 16)
#   --spp, --size  per job (default 64 spp at 1280x720)
#   --triangles T  the generated scene's size (default 1M; bench/gen_scene),
#                  unless a scene is given
#   --gpus SPEC    the --gpu of the second run (default all; e.g. 0,1)
#   --repeat K     timed runs of each kind, alternating (default 1)
#   --work DIR     scenes, manifest, outputs and logs (default bench/out/multigpu)
# Prints "gpu0_s", "multi_s" and "speedup" lines, then the jobs per worker;
# the JSON progress of each run is kept in --work. Record results in
# bench/RESULTS.md with the GPUs and the commit.
set -u

cmdline="bench/multigpu.sh $*"
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
binary=
jobs=16
spp=64
size=1280x720
triangles=1M
gpus=all
repeat=1
work=
scene=

while [ $# -gt 0 ]; do
    case "$1" in
    --binary) binary=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --triangles) triangles=$2; shift 2 ;;
    --gpus) gpus=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    -h|--help) bench_usage "$0"; exit 0 ;;
    -*) echo "multigpu.sh: unknown option $1" >&2; exit 2 ;;
    *) scene=$1; shift ;;
    esac
done

binary=$(bench_binary multigpu.sh "$binary" "$here/../src/cavalry-batch" "./src/cavalry-batch") || exit 2
binary=$(cd "$(dirname "$binary")" && pwd)/$(basename "$binary")
[ -n "$work" ] || work="$(dirname "$binary")/../bench/out/multigpu"
mkdir -p "$work" || exit 1
work=$(cd "$work" && pwd)

if [ -z "$scene" ]; then
    gen="$(dirname "$binary")/../bench/gen_scene"
    scene="$work/scene-$triangles/scene.pbrt"
    if [ ! -e "$scene" ]; then
        [ -x "$gen" ] || { echo "multigpu.sh: no $gen to make a scene; pass one" >&2; exit 2; }
        "$gen" --triangles "$triangles" --seed 1 --out "$work/scene-$triangles" >&2 || exit 1
    fi
fi
scene=$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")
w=${size%x*}
h=${size#*x}

# One job per seed: the same work for every job, outputs that differ.
manifest="$work/jobs.yaml"
{
    echo 'version: 1'
    echo "defaults: {scene: \"$scene\", output: \"out/{name}\", formats: [exr],"
    echo "           spp: $spp, resolution: [$w, $h]}"
    echo 'jobs:'
    i=0
    while [ "$i" -lt "$jobs" ]; do
        echo "  - {name: j$i, seed: $((i + 1))}"
        i=$((i + 1))
    done
} >"$manifest"

now() { date +%s.%N; }
# run LABEL GPU: one timed batch; prints its seconds
run() {
    rm -rf "$work/out"
    t0=$(now)
    (cd "$work" && "$binary" --gpu="$2" --force --progress=json jobs.yaml \
        >"$work/$1.jsonl" 2>"$work/$1.err")
    rc=$?
    t1=$(now)
    if [ "$rc" -ne 0 ]; then
        echo "multigpu.sh: --gpu=$2 exited with $rc; see $work/$1.err" >&2
        exit 1
    fi
    echo "$t0 $t1" | awk '{ printf "%.3f\n", $2 - $1 }'
}

"$binary" --list-gpus >&2 || exit 1
echo "warm-up (program cache)..." >&2
(cd "$work" && "$binary" --gpu=0 --force --only=j0 --progress=none jobs.yaml) >&2 || exit 1
k=0
while [ "$k" -lt "$repeat" ]; do
    single=$(run gpu0 0) || exit 1
    multi=$(run multi "$gpus") || exit 1
    echo "gpu0_s $single"
    echo "multi_s $multi"
    echo "$single $multi" | awk '{ printf "speedup %.2f\n", $1 / $2 }'
    k=$((k + 1))
done
echo "jobs per worker (gpu) of the last --gpu=$gpus run:"
grep '"event":"job_finished"' "$work/multi.jsonl" | grep -o '"gpu":[0-9]*,"worker":[0-9]*' |
    sed 's/"gpu":\([0-9]*\),"worker":\([0-9]*\)/  worker \2 (gpu \1)/' | sort | uniq -c
grep -q '"worker":' "$work/multi.jsonl" || echo "  (one process: --gpu=$gpus found one device)"
echo "command: $cmdline ($jobs jobs, $spp spp, ${w}x$h, $(basename "$scene"))"
