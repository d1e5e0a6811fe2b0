#!/bin/bash
# occ2.sh: traversal group 32/64/128 again (3 interleaved rounds) and the rows of the triangle
# test in shared memory (CV_BVH_SHARED_ROWS, group 64); images of that variant against main.
cd "$(dirname "$0")"
export LC_ALL=C
D=$PWD; SC=$PWD/../../.scenes; R=$OUT/r; mkdir -p $R; T0=$SECONDS
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
mk() { mkdir -p /tmp/v/$1; ln -sfn $D/configs /tmp/v/$1/configs; cp -r $2 /tmp/v/$1/glsl
  [ -n "$3" ] && sed -i "$4" /tmp/v/$1/glsl/$3; true; }
mk main $D/glsl_main
for g in 32 64 128; do mk g$g $D/glsl shared/trace.h "s/^#define CV_TRAVERSE_GROUP CV_TRACE_GROUP/#define CV_TRAVERSE_GROUP $g/"; done
mk sh $D/glsl trace/tracing.glsl 's/^#define CV_BVH_FAST_DIV$/#define CV_BVH_FAST_DIV\n#define CV_BVH_SHARED_ROWS/'
grep -h "define CV_TRAVERSE_GROUP [0-9]\|SHARED_ROWS" /tmp/v/*/glsl/shared/trace.h /tmp/v/*/glsl/trace/tracing.glsl
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
mkdir -p /tmp/img; cd /tmp/img
printf 'version: 1\ndefaults:\n  output: out/{name}\n  formats: [exr]\n  spp: 16\n  seed: 7\njobs:\n  - name: veach\n    scene: %s\n  - name: cornell\n    scene: %s\n  - name: g4\n    scene: %s\n    resolution: [640, 360]\n' \
  $SC/veach-bidir/scene-v4.pbrt $SC/cornell-box/scene-v4.pbrt $f > jobs.yaml
for v in main sh; do
  rm -rf out; CAVALRY_DATA_DIR=/tmp/v/$v CAVALRY_CACHE_DIR=/tmp/cc/$v $D/src/cavalry-batch -v --progress=none jobs.yaml > $R/img_$v.log 2>&1 || tail -3 $R/img_$v.log
  mkdir -p /tmp/imgs/$v; cp out/*.exr /tmp/imgs/$v/
done
for j in veach cornell g4; do echo "relmse sh $j $($D/bench/cavalry_bench --relmse /tmp/imgs/sh/$j.exr /tmp/imgs/main/$j.exr 2>&1 | tr '\n' ' ')"; done | tee $R/relmse.txt
mkdir -p $R/bin; grep -o "glsl/trace/\(intersect\|shadow\).comp written to [^ ]*" $R/img_sh.log | while read p _ _ file; do cp $file $R/bin/sh_$(basename $p .comp)_$(basename $file); done
cd $D; echo "img $((SECONDS-T0)) s"
export CAVALRY_STAGE_TIMES=1
for round in 1 2 3; do for v in g64 sh g128 g32; do
  [ $((SECONDS-T0)) -gt ${BUDGET:-205} ] && { echo "skip $round $v"; continue; }
  CAVALRY_DATA_DIR=/tmp/v/$v CAVALRY_CACHE_DIR=/tmp/cc/$v bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 2 --json >> $R/g4_$v.jsonl 2>>$R/g4_$v.err
  CAVALRY_DATA_DIR=/tmp/v/$v CAVALRY_CACHE_DIR=/tmp/cc/$v bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 512 --repeat 1 --json >> $R/veach_$v.jsonl 2>>$R/veach_$v.err
  echo "t $round $v $((SECONDS-T0)) s"
done; done
for v in g64 sh g128 g32; do
  echo "g4 $v $(grep -o '"render.stage.intersect_ms": [0-9.e+]*\|"render.stage.shadow_ms": [0-9.e+]*\|"render.traversal.closest_rays_per_s": [0-9.e+]*\|"render.traversal.shadow_rays_per_s": [0-9.e+]*' $R/g4_$v.jsonl | awk '{print $2}' | tr '\n' ' ')"
  echo "veach $v $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*\|"render.stage.intersect_ms": [0-9.e+]*\|"render.stage.shadow_ms": [0-9.e+]*' $R/veach_$v.jsonl | awk '{print $2}' | tr '\n' ' ')"
done
rm -f $R/img_*.log; tar -C $OUT -czf $OUT/occ2.tgz r && rm -rf $R
echo done $((SECONDS-T0)) s
