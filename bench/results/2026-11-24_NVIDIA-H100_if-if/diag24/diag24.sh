#!/bin/bash
# diag24.sh: traversal loop variants (glsl copies): interleaved node / triangle steps
cd "$(dirname "$0")"
export CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
bench/gen_scene --triangles 4M --seed 1 --indirect --out /tmp/g4i >/dev/null 2>&1; fi=$(ls /tmp/g4i/*.pbrt | head -1)
mk() { rm -rf /tmp/v_$1; mkdir -p /tmp/v_$1; cp -r glsl configs /tmp/v_$1/; }
mk base
for n in 1 2 4; do mk il$n; sed -i "s|^#define CV_BVH_TRAVERSE_GLSL|#define CV_BVH_TRAVERSE_GLSL\n#define CV_BVH_INTERLEAVE $n|" /tmp/v_il$n/glsl/bvh/traverse.glsl; done
grep -h "define CV_BVH_INTERLEAVE" /tmp/v_*/glsl/bvh/traverse.glsl
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
V="base il1 il2 il4"
for round in 1 2; do
for v in $V; do
  export CAVALRY_DATA_DIR=/tmp/v_$v
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4 --json > $R/g4s_${v}_$round.jsonl 2>$R/g4s_${v}_$round.err
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --json > $R/g4_${v}_$round.jsonl 2>$R/g4_${v}_$round.err
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $fi --width 1280 --height 720 --spp 64 --repeat 2 --json > $R/g4i_${v}_$round.jsonl 2>$R/g4i_${v}_$round.err
  bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 1024 --repeat 2 --json > $R/veach_${v}_$round.jsonl 2>$R/veach_${v}_$round.err
  echo "$v r$round first-bounce $(g render.traversal.first_bounce_rays_per_s $R/g4s_${v}_$round.jsonl) sec-only $(g render.traversal.secondary_only_rays_per_s $R/g4s_${v}_$round.jsonl)"
  echo "$v r$round g4 ms $(g render.time_to_spp_gpu_ms $R/g4_${v}_$round.jsonl) closest $(g render.traversal.closest_rays_per_s $R/g4_${v}_$round.jsonl) shadow $(g render.traversal.shadow_rays_per_s $R/g4_${v}_$round.jsonl)"
  echo "$v r$round g4i ms $(g render.time_to_spp_gpu_ms $R/g4i_${v}_$round.jsonl) closest $(g render.traversal.closest_rays_per_s $R/g4i_${v}_$round.jsonl) shadow $(g render.traversal.shadow_rays_per_s $R/g4i_${v}_$round.jsonl)"
  echo "$v r$round veach $(g render.time_to_spp_gpu_ms $R/veach_${v}_$round.jsonl)"
done
done
tar -C $OUT -czf $OUT/diag24.tgz r && rm -rf $R
echo done
