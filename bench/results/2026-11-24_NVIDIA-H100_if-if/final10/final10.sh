#!/bin/bash
# final10.sh: GPU tests, time to 1024 spp (veach-bidir, cornell-box), 4M scene open and --indirect (stage times; per-iteration rates)
cd "$(dirname "$0")"
export CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
TESTS="tests/gpu/compute_test tests/gpu/buffer_pool_test tests/gpu/storage_test tests/gpu/embedded_glsl_test.sh tests/trace/bsdf_energy_test tests/trace/bsdf_material_test tests/trace/rlpath_sample_test tests/trace/sampler_test tests/bvh/radix_sort_test tests/bvh/bvh_test tests/trace/analytic_test tests/trace/furnace_test tests/trace/passes_test tests/trace/cornell_test tests/trace/light_sampling_test tests/trace/bsdf_chi2_test tests/trace/rlpath_converge_test tests/batch/render_test.sh tests/batch/shared_scene_test.sh bench/bench_test.sh" ./gpu_tests.sh 2>&1 | tee $R/gpu_tests.txt | tail -22
for s in veach-bidir cornell-box; do bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 16 --repeat 1 >/dev/null 2>&1; done
for s in veach-bidir cornell-box; do
  bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 1024 --repeat 5 --json > $R/$s.jsonl 2>$R/$s.err
  echo "$s $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $R/$s.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
done
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 5 --json > $R/g4.jsonl 2>$R/g4.err
CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 5 --pass-spp 4 --json > $R/g4s.jsonl 2>$R/g4s.err
bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 5 --json > $R/g4_nostages.jsonl 2>$R/g4_nostages.err
bench/gen_scene --triangles 4M --seed 1 --indirect --out /tmp/g4i >/dev/null 2>&1; fi=$(ls /tmp/g4i/*.pbrt | head -1)
CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $fi --width 1280 --height 720 --spp 64 --repeat 3 --json > $R/g4i.jsonl 2>$R/g4i.err
CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $fi --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4 --json > $R/g4is.jsonl 2>$R/g4is.err
for v in g4 g4s g4_nostages g4i g4is; do
  echo "$v ms $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $R/$v.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$v closest $(grep -o '"render.traversal.closest_rays_per_s": [0-9.e+]*' $R/$v.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$v sec-only $(grep -o '"render.traversal.secondary_only_rays_per_s": [0-9.e+]*' $R/$v.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$v first-bounce $(grep -o '"render.traversal.first_bounce_rays_per_s": [0-9.e+]*' $R/$v.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$v shadow $(grep -o '"render.traversal.shadow_rays_per_s": [0-9.e+]*' $R/$v.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
  echo "$v secondary(whole) $(grep -o '"render.secondary_rays_per_s": [0-9.e+]*' $R/$v.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
done
for v in g4s g4is; do grep "intersect iteration" $R/$v.err | tail -n 9; done
tar -C $OUT -czf $OUT/final10.tgz r && rm -rf $R
echo done
