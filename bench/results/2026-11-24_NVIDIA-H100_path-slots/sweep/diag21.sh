#!/bin/bash
# diag21.sh: path slots per pixel: GPU tests; 4M scene K=1,2,4,8; secondary-only rates; veach/cornell K=1 vs auto
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
TESTS="tests/trace/passes_test tests/trace/analytic_test tests/trace/furnace_test tests/trace/cornell_test tests/trace/light_sampling_test tests/trace/rlpath_converge_test tests/batch/render_test.sh tests/batch/shared_scene_test.sh bench/bench_test.sh" ./gpu_tests.sh 2>&1 | tee $R/gpu_tests.txt | tail -15
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
K='"render.time_to_spp_gpu_ms": [0-9.e+]*\|"render.paths_per_pixel": [0-9]*\|"render.iterations": [0-9]*\|"render.traversal.closest_rays_per_s": [0-9.e+]*\|"render.traversal.shadow_rays_per_s": [0-9.e+]*\|"render.traversal.secondary_only_rays_per_s": [0-9.e+]*\|"render.traversal.camera_only_rays_per_s": [0-9.e+]*\|"gpu.peak_used_mib": [0-9.e+]*'
for k in 1 2 4 8 0; do
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 4 --paths-per-pixel $k --json > $R/g4_k$k.jsonl 2>$R/g4_k$k.err
  grep -o "$K" $R/g4_k$k.jsonl | tr '\n' ' ' | sed 's/"render.time_to_spp_gpu_ms"/\n/g' | sed "s/^/g4 k$k /"; echo
done
for k in 1 4 8; do
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 4 --paths-per-pixel $k --pass-spp $k --json > $R/g4s_k$k.jsonl 2>$R/g4s_k$k.err
  grep -o "$K" $R/g4s_k$k.jsonl | tr '\n' ' ' | sed 's/"render.time_to_spp_gpu_ms"/\n/g' | sed "s/^/g4-sec k$k /"; echo
done
for s in veach-bidir cornell-box; do bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 16 --repeat 1 >/dev/null 2>&1; done
for round in 1 2; do
for s in veach-bidir cornell-box; do
  for k in 1 0; do
  bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 1024 --repeat 3 --paths-per-pixel $k --json > $R/${s}_k${k}_$round.jsonl 2>$R/${s}_k$k_$round.err
  echo "$s k$k round$round $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $R/${s}_k${k}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  done
done
done
tar -C $OUT -czf $OUT/diag21.tgz r && rm -rf $R
echo done
