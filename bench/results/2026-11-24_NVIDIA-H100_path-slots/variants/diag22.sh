#!/bin/bash
# diag22.sh: traversal variants (glsl copies): restrict, SAH inner cost, max leaf size
cd "$(dirname "$0")"
export CAVALRY_CACHE_DIR=/tmp/cvcache LC_ALL=C
SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R
bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
mk() { rm -rf /tmp/v_$1; mkdir -p /tmp/v_$1; cp -r glsl configs /tmp/v_$1/; }
mk base
mk restrict; sed -i 's/readonly buffer CvBvhNodeBuffer/restrict readonly buffer CvBvhNodeBuffer/; s/readonly buffer CvBvhTriBuffer/restrict readonly buffer CvBvhTriBuffer/' /tmp/v_restrict/glsl/bvh/scene_buffers.glsl
mk ci1; sed -i 's/#define CV_BVH_COST_INNER 1.2/#define CV_BVH_COST_INNER 1.0/' /tmp/v_ci1/glsl/shared/bvh.h
mk ci2; sed -i 's/#define CV_BVH_COST_INNER 1.2/#define CV_BVH_COST_INNER 2.0/' /tmp/v_ci2/glsl/shared/bvh.h
mk leaf4; sed -i 's/#define CV_BVH_MAX_LEAF 8/#define CV_BVH_MAX_LEAF 4/' /tmp/v_leaf4/glsl/shared/bvh.h
mk leaf16; sed -i 's/#define CV_BVH_MAX_LEAF 8/#define CV_BVH_MAX_LEAF 16/' /tmp/v_leaf16/glsl/shared/bvh.h
grep -c restrict /tmp/v_restrict/glsl/bvh/scene_buffers.glsl; grep -h "COST_INNER\|MAX_LEAF" /tmp/v_ci1/glsl/shared/bvh.h /tmp/v_leaf16/glsl/shared/bvh.h
V="base restrict ci1 ci2 leaf4 leaf16"
for round in 1 2; do
for v in $V; do
  export CAVALRY_DATA_DIR=/tmp/v_$v
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4 --paths-per-pixel 4 --json > $R/g4s_${v}_$round.jsonl 2>$R/g4s_${v}_$round.err
  CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --json > $R/g4_${v}_$round.jsonl 2>$R/g4_${v}_$round.err
  bench/cavalry_bench --bench $SC/veach-bidir/scene-v4.pbrt --spp 1024 --repeat 2 --json > $R/veach_${v}_$round.jsonl 2>$R/veach_${v}_$round.err
  echo "$v r$round sec-only $(grep -o '"render.traversal.secondary_only_rays_per_s": [0-9.e+]*' $R/g4s_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ') | g4 ms $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $R/g4_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ') closest $(grep -o '"render.traversal.closest_rays_per_s": [0-9.e+]*' $R/g4_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ') sah $(grep -o '"bvh.sah_cost": [0-9.e+]*' $R/g4_${v}_$round.jsonl | head -1 | cut -d' ' -f2) | veach $(grep -o '"render.time_to_spp_gpu_ms": [0-9.e+]*' $R/veach_${v}_$round.jsonl | cut -d' ' -f2 | tr '\n' ' ')"
done
done
tar -C $OUT -czf $OUT/diag22.tgz r && rm -rf $R
echo done
