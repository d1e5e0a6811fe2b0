#!/bin/bash
# diag37.sh: diag33 and diag34 again after the stack fix (64 entries) and with the stack need: bvh_test, bvh_bench 4M and 16M (with --check), then the render A/B
cd "$(dirname "$0")"
export LC_ALL=C
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/gpu.txt
run() { local v=$1; shift; (cd $v && CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache_$v "$@"); }
run new tests/bvh/bvh_test > $R/bvh_test_new.txt 2>&1
echo "bvh_test new: $(grep -c '^ok' $R/bvh_test_new.txt) ok, $(grep -c '^not ok' $R/bvh_test_new.txt) not ok"
run new tests/bvh/bvh_bench 4000000 --reps 1 --check > $R/bvhb4_check.txt 2>&1; grep -E "check|nodes " $R/bvhb4_check.txt; run new tests/bvh/bvh_bench 16000000 --reps 1 --check > $R/bvhb16_check.txt 2>&1; grep -E "check|nodes " $R/bvhb16_check.txt
for v in base new; do
  run $v tests/bvh/bvh_bench 4000000 --reps 9 --rays 4000000 > $R/bvhb4_$v.txt 2>&1
  echo "$v 4M: $(grep -E '^  (total|widen|collapse) ' $R/bvhb4_$v.txt | tr -s ' ' | tr '\n' ';') $(grep -E 'Mrays/s|nodes visited' $R/bvhb4_$v.txt | tr -s ' ' | tr '\n' ';')"
  run $v tests/bvh/bvh_bench 16000000 --reps 5 > $R/bvhb16_$v.txt 2>&1
  echo "$v 16M: $(grep -E '^  (total|widen|collapse|wall) ' $R/bvhb16_$v.txt | tr -s ' ' | tr '\n' ';') $(grep -E '^  nodes' $R/bvhb16_$v.txt)"
done
tar -C $OUT -czf $OUT/diag37a.tgz r && rm -rf $R

SC=$PWD/../../.scenes
R=$OUT/r; mkdir -p $R

run() { local v=$1; shift; (cd $v && CAVALRY_DATA_DIR=$PWD CAVALRY_CACHE_DIR=/tmp/cvcache_$v "$@"); }
new/bench/gen_scene --triangles 4M --seed 1 --out /tmp/g4 >/dev/null 2>&1; f=$(ls /tmp/g4/*.pbrt | head -1)
new/bench/gen_scene --triangles 4M --seed 1 --indirect --out /tmp/g4i >/dev/null 2>&1; fi=$(ls /tmp/g4i/*.pbrt | head -1)
g() { grep -o "\"$1\": [0-9.e+]*" $2 | cut -d' ' -f2 | tr '\n' ' '; }
for v in base new; do run $v bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 16 --repeat 1 >/dev/null 2>&1; done
for round in 1 2; do
  for v in base new; do
    run $v env CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4 --json > $R/g4s_${v}_$round.jsonl 2>$R/g4s_${v}_$round.err
    run $v env CAVALRY_STAGE_TIMES=1 bench/cavalry_bench --bench $fi --width 1280 --height 720 --spp 64 --repeat 3 --pass-spp 4 --json > $R/g4is_${v}_$round.jsonl 2>$R/g4is_${v}_$round.err
    run $v bench/cavalry_bench --bench $f --width 1280 --height 720 --spp 64 --repeat 5 --json > $R/g4_${v}_$round.jsonl 2>$R/g4_${v}_$round.err
    for s in veach-bidir cornell-box; do run $v bench/cavalry_bench --bench $SC/$s/scene-v4.pbrt --spp 1024 --repeat 3 --json > $R/${s}_${v}_$round.jsonl 2>$R/${s}_${v}_$round.err; done
    echo "r$round $v g4s first $(g render.traversal.first_bounce_rays_per_s $R/g4s_${v}_$round.jsonl)| sec $(g render.traversal.secondary_only_rays_per_s $R/g4s_${v}_$round.jsonl)| shadow $(g render.traversal.shadow_rays_per_s $R/g4s_${v}_$round.jsonl)"
    echo "r$round $v g4is first $(g render.traversal.first_bounce_rays_per_s $R/g4is_${v}_$round.jsonl)| sec $(g render.traversal.secondary_only_rays_per_s $R/g4is_${v}_$round.jsonl)"
    echo "r$round $v g4 64spp $(g render.time_to_spp_gpu_ms $R/g4_${v}_$round.jsonl)| veach $(g render.time_to_spp_gpu_ms $R/veach-bidir_${v}_$round.jsonl)| cornell $(g render.time_to_spp_gpu_ms $R/cornell-box_${v}_$round.jsonl)"
  done
done
tar -C $OUT -czf $OUT/diag37b.tgz r && rm -rf $R
echo done
