#!/bin/bash
# occ1.sh: traversal work-group size sweep (CV_TRAVERSE_GROUP) and BVH stack size, one run;
# program binaries of intersect/shadow dumped for register counts. Run from the staged folder.
cd "$(dirname "$0")"
export LC_ALL=C
D=$PWD; SC=$PWD/../../.scenes; R=$OUT/r; mkdir -p $R; T0=$SECONDS
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
mk() { # NAME GLSLSRC SEDFILE SEDEXPR
  mkdir -p /tmp/v/$1; ln -sfn $D/configs /tmp/v/$1/configs; cp -r $2 /tmp/v/$1/glsl
  [ -n "$3" ] && sed -i "$4" /tmp/v/$1/glsl/$3; true; }
mk main $D/glsl_main
for g in 32 64 128 256; do mk g$g $D/glsl shared/trace.h "s/^#define CV_TRAVERSE_GROUP CV_TRACE_GROUP/#define CV_TRAVERSE_GROUP $g/"; done
for s in 32 48; do mk s$s $D/glsl bvh/traverse.glsl "s/^#define CV_BVH_STACK_SIZE 64/#define CV_BVH_STACK_SIZE $s/"; done
grep -h "define CV_TRAVERSE_GROUP [0-9]\|define CV_BVH_STACK_SIZE" /tmp/v/*/glsl/shared/trace.h /tmp/v/*/glsl/bvh/traverse.glsl
V="g64 g128 g256 g32 s32 s48"
tests/bvh/bvh_bench 4000000 --reps 1 --check 2>&1 | grep -v '^GPU' | tee $R/bvh4m.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
echo "gen $((SECONDS-T0)) s"
# images at 16 spp (and the program binaries, logged by cavalry-batch -v)
mkdir -p /tmp/img; cd /tmp/img
printf 'version: 1\ndefaults:\n  output: out/{name}\n  formats: [exr]\n  spp: 16\n  seed: 7\njobs:\n  - name: veach\n    scene: %s\n  - name: cornell\n    scene: %s\n  - name: g4\n    scene: %s\n    resolution: [640, 360]\n' \
  $SC/veach-bidir/scene-v4.pbrt $SC/cornell-box/scene-v4.pbrt $f > jobs.yaml
for v in main $V; do
  rm -rf out; CAVALRY_DATA_DIR=/tmp/v/$v CAVALRY_CACHE_DIR=/tmp/cc/$v $D/src/cavalry-batch -v --progress=none jobs.yaml > $R/img_$v.log 2>&1 || tail -3 $R/img_$v.log
  mkdir -p /tmp/imgs/$v; cp out/*.exr /tmp/imgs/$v/
done
for v in $V; do for j in veach cornell g4; do
  echo "relmse $v $j $($D/bench/cavalry_bench --relmse /tmp/imgs/$v/$j.exr /tmp/imgs/main/$j.exr 2>&1 | tr '\n' ' ')"; done; done | tee $R/relmse.txt
cd $D; echo "img $((SECONDS-T0)) s"
mkdir -p $OUT/bin
for v in main g64 g128 s32; do
  grep -o "glsl/trace/\(intersect\|shadow\).comp written to [^ ]*" $R/img_$v.log | while read p _ _ file; do
    b=$(basename $p .comp); cp $file $OUT/bin/${v}_${b}_$(basename $file); done; done
ls -la $OUT/bin | head -30
# timings: 4M scene at 64 spp and veach-bidir 512 spp, interleaved rounds
export CAVALRY_STAGE_TIMES=1
for round in 1 2; do for v in $V; do
  [ $((SECONDS-T0)) -gt ${BUDGET:-215} ] && { echo "skip $round $v"; continue; }
  CAVALRY_DATA_DIR=/tmp/v/$v CAVALRY_CACHE_DIR=/tmp/cc/$v bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 2 --json >> $R/g4_$v.jsonl 2>>$R/g4_$v.err
  CAVALRY_DATA_DIR=/tmp/v/$v CAVALRY_CACHE_DIR=/tmp/cc/$v bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 512 --repeat 2 --json >> $R/veach_$v.jsonl 2>>$R/veach_$v.err
  echo "t $round $v $((SECONDS-T0)) s"
done; done
for v in $V; do
  echo "g4 $v $(grep -o '"render.traversal.closest_rays_per_s": [0-9.e+]*\|"render.traversal.shadow_rays_per_s": [0-9.e+]*\|"render.stage.intersect_ms": [0-9.e+]*\|"render.stage.shadow_ms": [0-9.e+]*' $R/g4_$v.jsonl | awk '{print $2}' | tr '\n' ' ')"
  echo "veach $v $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*\|"render.stage.intersect_ms": [0-9.e+]*\|"render.stage.shadow_ms": [0-9.e+]*' $R/veach_$v.jsonl | awk '{print $2}' | tr '\n' ' ')"
done
echo done $((SECONDS-T0)) s
