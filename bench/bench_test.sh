#!/bin/sh
# bench_test.sh: the benchmark tools on tiny inputs: gen_scene writes exactly
# the requested triangles, deterministically per seed, in well-formed PLY
# that the scene loader reads; plot draws a PNG; the summariser takes the
# median of repeats; coldstart.sh times a cold start.
. "${CAVALRY_DATA_DIR:?}/tests/setup.sh"
bdir=$(dirname "$(dirname "$CAVALRY_BATCH")")
gen="$bdir/bench/gen_scene"
plot="$bdir/bench/plot"
cb="$bdir/bench/cavalry_bench"

# Sum of "element face N" over the PLY headers of a scene folder.
faces() {
    total=0
    for f in "$1"/geometry/*.ply; do
        n=$(sed -n '/^end_header/q; s/^element face //p' "$f" 2>/dev/null | head -n 1)
        total=$((total + n))
    done
    echo "$total"
}

check "gen_scene writes a scene" "$gen" --triangles 5000 --seed 3 --out "$tmp/a" 2>/dev/null
check "scene.pbrt is there" test -s "$tmp/a/scene.pbrt"
check "exactly 5000 triangles (got $(faces "$tmp/a"))" test "$(faces "$tmp/a")" -eq 5000
"$gen" --triangles 5000 --seed 3 --out "$tmp/b" 2>/dev/null
check "same seed gives the same bytes" diff -r "$tmp/a" "$tmp/b"
"$gen" --triangles 5000 --seed 4 --out "$tmp/c" 2>/dev/null
check "another seed gives another scene" sh -c "! diff -rq '$tmp/a' '$tmp/c' >/dev/null"
check "several PLY files (objects)" test "$(ls "$tmp/a/geometry" | wc -l)" -gt 10
check "binary little-endian PLY" grep -aq "format binary_little_endian 1.0" "$tmp/a/geometry/ground.ply"
for m in diffuse conductor dielectric coateddiffuse; do
    check "material type $m" grep -q "\"string type\" \"$m\"" "$tmp/a/scene.pbrt"
done
check "area lights and a distant light" sh -c \
    "grep -q AreaLightSource '$tmp/a/scene.pbrt' && grep -q '\"distant\"' '$tmp/a/scene.pbrt'"
"$gen" --triangles 7001 --seed 1 --indirect --out "$tmp/d" 2>/dev/null
check "indirect: exactly 7001 triangles" test "$(faces "$tmp/d")" -eq 7001
check "indirect: no distant or environment light" sh -c "! grep -q '^LightSource' '$tmp/d/scene.pbrt'"
check "too few triangles is refused" sh -c "! '$gen' --triangles 10 --out '$tmp/e' 2>/dev/null"
check "a bad number is refused" sh -c "! '$gen' --triangles 5x --out '$tmp/e' 2>/dev/null"

"$gen" --triangles 6000 --seed 2 --production --out "$tmp/p" 2>/dev/null
check "production: exactly 6000 triangles" test "$(faces "$tmp/p")" -eq 6000
check "production: at least 50 materials" \
    test "$(grep -c '^MakeNamedMaterial' "$tmp/p/scene.pbrt")" -ge 50
for m in coateddiffuse coatedconductor conductor dielectric; do
    check "production: material type $m" grep -q "\"string type\" \"$m\"" "$tmp/p/scene.pbrt"
done
check "production: image textures used by materials" grep -q '"texture reflectance" "tex_' "$tmp/p/scene.pbrt"
check "production: textures of several sizes (64 to 2048)" sh -c \
    "test \$(ls -l '$tmp/p/textures' | awk '/tex_/ {print \$5}' | sort -u | wc -l) -ge 6"
check "production: meshes carry texture coordinates" \
    grep -aq "property float u" "$tmp/p/geometry/ground.ply"
"$gen" --triangles 6000 --seed 2 --production --out "$tmp/p2" 2>/dev/null
check "production: same seed gives the same bytes" diff -r "$tmp/p" "$tmp/p2"

# The loader reads what the generator writes (when it is in this build).
"$cb" --bench "$tmp/a/scene.pbrt" --no-gpu > "$tmp/rec.jsonl" 2>"$tmp/err" || true
if grep -q '"unavailable.load"' "$tmp/rec.jsonl"; then
    ok "# SKIP scene loader not in this build"
else
    check "the loader reads 5000 triangles" grep -q '"scene.triangles": 5000[,}]' "$tmp/rec.jsonl"
    check "without warnings" grep -q '"scene.warnings": 0[,}]' "$tmp/rec.jsonl"
    "$cb" --bench "$tmp/p/scene.pbrt" --no-gpu > "$tmp/recp.jsonl" 2>"$tmp/errp" || true
    check "production: the loader reads 6000 triangles" \
        grep -q '"scene.triangles": 6000[,}]' "$tmp/recp.jsonl"
    check "production: without warnings" grep -q '"scene.warnings": 0[,}]' "$tmp/recp.jsonl"
    check "production: 64 materials and more" sh -c \
        "grep -o '\"scene.materials\": [0-9]*' '$tmp/recp.jsonl' | awk '{exit !(\$2 >= 64)}'"
fi

printf 'spp,seconds,relmse\n1,0.1,1\n2,0.2,0.5\n4,0.4,0.25\n' > "$tmp/s.csv"
check "plot writes a PNG" "$plot" --out "$tmp/p.png" --title "t" "$tmp/s.csv=path"
check "the PNG has the PNG signature" sh -c "head -c 8 '$tmp/p.png' | od -An -c | grep -q 'P   N   G'"
check "plot refuses a missing column" sh -c "! '$plot' --out '$tmp/q.png' --y nope '$tmp/s.csv' 2>/dev/null"

for v in 1 5 3; do
    echo "{\"scene\": \"x\", \"repeat\": 0, \"load.wall_ms\": $v, \"unavailable.bvh\": \"why\"}"
done > "$tmp/runs.jsonl"
"$cb" --summarize "$tmp/runs.jsonl" > "$tmp/sum.json" 2>/dev/null
check "summary: median of 1, 5, 3 is 3" grep -q '"load.wall_ms": {"median": 3, "min": 1, "max": 5' "$tmp/sum.json"
check "summary lists what is unavailable" grep -q '"unavailable": {"bvh": "why"}' "$tmp/sum.json"

# multigpu.sh on llvmpipe's one device, two workers on it: both wall times
# and a speed-up are printed, and the jobs are spread over the workers.
if "$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1; then
    check_out "multigpu.sh runs" "$tmp/mg.out" sh "$CAVALRY_DATA_DIR/bench/multigpu.sh" \
        --binary "$CAVALRY_BATCH" --work "$tmp/mg" --jobs 4 --spp 1 --size 16x9 \
        --gpus 0,0 "$tmp/a/scene.pbrt" 2>"$tmp/mg.err"
    check "multigpu.sh prints both times and the speed-up" sh -c "grep -q '^gpu0_s [0-9.]*\$' \
        '$tmp/mg.out' && grep -q '^multi_s [0-9.]*\$' '$tmp/mg.out' && grep -q '^speedup ' '$tmp/mg.out'"
    check "multigpu.sh counts the jobs of each worker" grep -q 'worker [01] (gpu 0)' "$tmp/mg.out"
fi
# bvh_work: the CPU walk agrees with the GPU's traversal (hits and nodes
# visited) on the generated scene, and every query type is reported, for the
# renderer's tree and the CPU reference.
bw="$bdir/bench/bvh_work"
if "$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1; then
    check_out "bvh_work --verify --ref runs" "$tmp/bw.out" "$bw" "$tmp/a/scene.pbrt" --res 24 \
        --verify --ref --ref-widen greedy 2>/dev/null
    check "bvh_work: the walk matches the GPU's" grep -q '^verify: .* 0 with another hit' "$tmp/bw.out"
    check "bvh_work: every query type, both trees" test "$(grep -cE '^  (camera|bounce1|bounce2|shadow) ' \
        "$tmp/bw.out")" -eq 8
    # the renderer's binary tree widened on the CPU by its own rule (least
    # node area) is its tree
    check_out "bvh_work --rewiden sah runs" "$tmp/bw2.out" "$bw" "$tmp/a/scene.pbrt" --res 24 \
        --rewiden sah --wide 4 2>/dev/null
    check "bvh_work: the GPU's widening is the least-area rule" test \
        "$(grep -c "$(grep -m1 '^  all queries' "$tmp/bw2.out")" "$tmp/bw2.out")" -eq 2
    check "bvh_work: the same node count, depth and children per node" test \
        "$(grep 'nodes, depth' "$tmp/bw2.out" | sed 's/^[^:]*: //' | uniq | wc -l)" -eq 1
fi
# coldstart.sh on one cold run of rlpath's sdtree method: the first pass's
# medians, and when the parallel run got its last programs (the GPU
# context's clock of the -v log); cavalry_bench refuses a method it does
# not know.
if "$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1; then
    check_out "coldstart.sh runs sdtree" "$tmp/cs.out" sh "$CAVALRY_DATA_DIR/bench/coldstart.sh" \
        --binary "$cb" --repeat 1 --modes parallel --size 16x9 --integrator rlpath-sdtree \
        --work "$tmp/cs" "$tmp/a/scene.pbrt" 2>"$tmp/cs.err"
    check "coldstart.sh: a first pass time" \
        grep -qE '^[^ ]*scene.pbrt +parallel +[0-9.]+ ' "$tmp/cs.out"
    check "coldstart.sh: when the parallel run got sdtree's shade program" \
        grep -qE '^ +[0-9]+ +[0-9]+ +[0-9.]+  trace/rlpath/sd_shade.comp ' "$tmp/cs.out"
    # the guide's choice after training: its figures, and the choice z
    # gives (guided only below -2: src/trace/guide_choice.c)
    "$cb" --bench "$tmp/a/scene.pbrt" --spp 96 --width 16 --height 9 --integrator rlpath \
        --rl-method sdtree > "$tmp/ch.jsonl" 2>/dev/null || true
    check "cavalry_bench records the guide's choice's figures" sh -c "grep -q \
        '\"render.choice_err_guided\": [0-9]' '$tmp/ch.jsonl' && grep -q \
        '\"render.choice_ms_path\": [0-9]' '$tmp/ch.jsonl'"
    check "cavalry_bench: the passes after training went the way z says" sh -c "awk '
        { if (match(\$0, /\"render.choice_z\": [-+0-9.e]+/)) z = substr(\$0, RSTART + 18, RLENGTH - 18)
          if (match(\$0, /\"render.unguided\": [01]/)) u = substr(\$0, RSTART + 19, 1) }
        END { exit !(z != \"\" && u != \"\" && (u == 1) == (z + 0 >= -2)) }' '$tmp/ch.jsonl'"
    # --rl-fallback false keeps guiding: no choice measured
    "$cb" --bench "$tmp/a/scene.pbrt" --spp 96 --width 16 --height 9 --integrator rlpath \
        --rl-method sdtree --rl-fallback false > "$tmp/nf.jsonl" 2>/dev/null || true
    check "cavalry_bench --rl-fallback false: guided on, no choice measured" sh -c "grep -q \
        '\"render.unguided\": 0[,}]' '$tmp/nf.jsonl' && ! grep -q choice_z '$tmp/nf.jsonl'"
    check "cavalry_bench refuses --rl-fallback maybe" sh -c "! '$cb' --bench '$tmp/a/scene.pbrt' \
        --spp 1 --width 8 --height 8 --integrator rlpath --rl-fallback maybe >/dev/null 2>&1"
    check "cavalry_bench refuses an unknown rlpath method" sh -c "! '$cb' --bench \
        '$tmp/a/scene.pbrt' --spp 1 --width 8 --height 8 --integrator rlpath --rl-method nope \
        >/dev/null 2>&1"
fi
# guiding.sh refuses --rl's training for a variant that sets its own,
# before it renders anything
rc=0
sh "$CAVALRY_DATA_DIR/bench/guiding.sh" --rl "mix: 0.5, train: 4" --variants "path rlpath-online" \
    --work "$tmp/g" >"$tmp/g.out" 2>"$tmp/g.err" || rc=$?
check "guiding.sh: --rl train with rlpath-online is a usage error" test "$rc" -eq 2
check "guiding.sh: which says why" grep -q 'sets train, which the variant rlpath-online' \
    "$tmp/g.err"
check "guiding.sh: and made no work folder" test ! -e "$tmp/g"
# guiding.sh reads a relative --scenes from where it was started
if "$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1; then
    mkdir -p "$tmp/sc" && cp -R "$tmp/a" "$tmp/sc/tiny" &&
        mv "$tmp/sc/tiny/scene.pbrt" "$tmp/sc/tiny/scene-v4.pbrt"
    (cd "$tmp" && sh "$CAVALRY_DATA_DIR/bench/guiding.sh" --batch "$CAVALRY_BATCH" --bench "$cb" \
        --scenes sc --variants path --seeds 1 --spp 2 --ref-spp 4 --size 8x8 --work g2 tiny \
        >"$tmp/g2.out" 2>"$tmp/g2.err") || true
    check "guiding.sh: a relative --scenes renders the scene" grep -q '^tiny,path,0,1,' \
        "$tmp/g2/runs.csv"
fi
# rt_probe (built where configure found Vulkan and glslangValidator): the
# same ray set as bvh_work (bench/rays.c), spawned from the GPU traversal's
# hits, timed per query type; the Vulkan columns where a device traces
# with ray-tracing pipelines, else the reason why not.
rp="$bdir/bench/rt_probe"
if test -x "$rp" && "$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1; then
    check_out "rt_probe runs" "$tmp/rp.out" "$rp" "$tmp/a/scene.pbrt" --res 24 --repeats 3 2>/dev/null
    for q in camera bounce1 bounce2 shadow; do
        check "rt_probe: $q rays as bvh_work made them" test \
            "$(awk -v q=$q '$1 == q {print $2; exit}' "$tmp/rp.out")" = \
            "$(awk -v q=$q '$1 == q {print $2; exit}' "$tmp/bw.out")"
    done
    check "rt_probe: a rate for every query type and all" test \
        "$(grep -cE '^(camera|bounce1|bounce2|shadow|all) +[0-9]+ +[0-9.]+ +[0-9.]+' "$tmp/rp.out")" -eq 5
    check "rt_probe: the Vulkan line" grep -qE '^vulkan: ' "$tmp/rp.out"
    if grep -q '^vulkan: unavailable' "$tmp/rp.out"; then
        ok "# SKIP rt_probe: no Vulkan device with ray-tracing pipelines"
    else
        check "rt_probe: every closest hit and occlusion the same on both back ends" test \
            "$(awk '$1 ~ /^(camera|bounce1|bounce2|shadow)$/ && $8 < 99 {n++} END {print n + 0}' \
            "$tmp/rp.out")" -eq 0
    fi
    check_out "rt_probe --shuffle runs" "$tmp/rps.out" "$rp" "$tmp/a/scene.pbrt" --res 24 --repeats 3 --shuffle 2>/dev/null
    check "rt_probe --shuffle says so" grep -q 'seed 1, shuffled;' "$tmp/rps.out"
    check "rt_probe: pixel order by default" grep -q 'seed 1, in pixel order;' "$tmp/rp.out"
    for q in camera bounce1 bounce2 shadow; do
        check "rt_probe --shuffle: as many $q rays" test \
            "$(awk -v q=$q '$1 == q {print $2; exit}' "$tmp/rps.out")" = \
            "$(awk -v q=$q '$1 == q {print $2; exit}' "$tmp/rp.out")"
    done
    check "rt_probe refuses an unknown option" sh -c "! '$rp' '$tmp/a/scene.pbrt' --nope 2>/dev/null"
fi
done_testing
