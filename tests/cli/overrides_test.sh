#!/bin/sh
# overrides_test.sh: the command line's overrides. --spp, --resolution and
# --time-limit (the manifest's duration units) reach the plan, --dry-run and
# --dry-run --json show them, and --resume's settings hash sees them (an
# override equal to the manifest's value is the same render); --output-dir
# moves the outputs (an absolute one too, with their locks and --resume; an
# absolute template outside the manifest's folder stays); --only is
# repeatable and takes globs; "-" reads the manifest from standard input; a
# bad flag is one line and a "Try" line.
. "${srcdir:-.}/tests/setup.sh"
py=/usr/bin/python3
[ -x "$py" ] || skip_all "no $py"
checker="$CV_TEST_DATA/../batch/progress_check.py"
data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$data/jobs.yaml" "$tmp/"
cd "$tmp"

# Usage errors, GNU style: the error, then how to get help; exit 2.
for args in "--no-such-flag" "--spp=0" "--spp=x" "--resolution=8" "--resolution=0x4" \
            "--time-limit=2x" "--time-limit=0" "--json" "--progress=loud" "--worker=x" \
            "--shard-count=0" "--shard-index=0 --shard-count=0"; do
    "$CAVALRY_BATCH" $args jobs.yaml >/dev/null 2>usage.err && rc=0 || rc=$?
    check "$args: exit 2 (got $rc)" test "$rc" -eq 2
    check "$args: two lines" test "$(wc -l <usage.err)" -eq 2
    check "$args: Try line" test "$(tail -n 1 usage.err)" = \
        "Try 'cavalry-batch --help' for more information."
done
"$CAVALRY_BATCH" --spp=99999999 jobs.yaml >/dev/null 2>range.err || :
check "--spp out of the key table's range" grep -q '^error: --spp: 99999999 is not in \[1, 16777216\]' range.err

# The plan with overrides, as a submitter reads it.
check_out "dry-run json" plan.json "$CAVALRY_BATCH" --dry-run --json --spp 3 --resolution 8x6 \
    --time-limit 1.5m --output-dir "$tmp/elsewhere" jobs.yaml 2>plan.err
check "overrides in the plan" "$py" "$checker" dryrun plan.json jobs=a,b,c a.spp=3 b.spp=3 \
    a.resolution=[8,6] c.resolution=[8,6] a.time_limit=90 a.seed=7 a.integrator='"path"' \
    "a.outputs=[\"$tmp/elsewhere/out/a.exr\",\"$tmp/elsewhere/out/a.png\"]" \
    "c.outputs=[\"$tmp/elsewhere/out/c.png\"]" a.shard=0
check_out "dry-run json without overrides" plain.json "$CAVALRY_BATCH" --dry-run --json jobs.yaml
check "the manifest's values" "$py" "$checker" dryrun plain.json a.spp=4 b.spp=2 \
    a.resolution=[16,12] c.resolution=[8,6] a.time_limit=null "a.outputs=[\"out/a.exr\",\"out/a.png\"]"
check_out "dry-run text" plan.txt "$CAVALRY_BATCH" --dry-run --spp 3 --resolution 8x6 jobs.yaml
check "dry-run text shows them" grep -qx 'b: tiny.pbrt -> out/b \[exr,png\] 8x6, 3 spp' plan.txt
"$CAVALRY_BATCH" --shard-count=0 jobs.yaml >/dev/null 2>zero.err || :
check "--shard-count=0 says so" grep -qx 'error: --shard-count must be at least 1' zero.err
"$CAVALRY_BATCH" --worker=x jobs.yaml >/dev/null 2>worker.err || :
check "--worker=x says why" grep -q '^error: --worker wants a GPU index' worker.err
check_out "dry-run text, time limit" tl.txt "$CAVALRY_BATCH" --dry-run --time-limit 1.5m jobs.yaml
check "dry-run text shows the time limit applied" grep -q '^b: tiny.pbrt -> out/b .*, at most 90 s$' tl.txt
check_out "2h" h.json "$CAVALRY_BATCH" --dry-run --json --time-limit 2h jobs.yaml
check "2h is 7200 s" "$py" "$checker" dryrun h.json a.time_limit=7200
check_out "plain seconds" s.json "$CAVALRY_BATCH" --dry-run --json --time-limit 90 jobs.yaml
check "90 is 90 s" "$py" "$checker" dryrun s.json a.time_limit=90
check_out "shards listed for a submitter" shards.json "$CAVALRY_BATCH" --dry-run --json \
    --shard-count 2 jobs.yaml
check "each job with its shard" "$py" "$checker" dryrun shards.json jobs=a,b,c a.shard=0 b.shard=1 c.shard=0

# --only: repeatable, globs, and a pattern matching nothing is an error.
printf 'version: 1\ndefaults:\n  scene: tiny.pbrt\n  output: out/{name}\njobs:\n  - name: cam-a\n  - name: cam-b\n  - name: light-a\n  - name: x1\n' >many.yaml
check_out "--only globs" only.json "$CAVALRY_BATCH" --dry-run --json --only 'cam-*' --only x? many.yaml
check "cam-a, cam-b and x1" "$py" "$checker" dryrun only.json jobs=cam-a,cam-b,x1
check_out "--only a bracket class" br.json "$CAVALRY_BATCH" --dry-run --json --only '*-[a]' many.yaml
check "cam-a and light-a" "$py" "$checker" dryrun br.json jobs=cam-a,light-a
"$CAVALRY_BATCH" --dry-run --only 'cam-*' --only 'nope*' many.yaml >/dev/null 2>nomatch.err && rc=0 || rc=$?
check "--only matching nothing: exit 3 (got $rc)" test "$rc" -eq 3
check "--only matching nothing: said" grep -q 'no job matches "nope\*"' nomatch.err

# Standard input: the same plan as the file; paths from the working folder.
check_out "manifest on stdin" stdin.json sh -c "\"$CAVALRY_BATCH\" --dry-run --json - <jobs.yaml"
check "stdin: the same jobs" "$py" "$checker" dryrun stdin.json jobs=a,b,c a.spp=4 c.resolution=[8,6]
check "stdin: named <stdin>" grep -q '"manifest":"<stdin>"' stdin.json

# Rendering: the override reaches the image and the settings hash.
if "$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1; then
    check_out "render --spp 3 --output-dir" r0.jsonl "$CAVALRY_BATCH" --progress=json --spp 3 \
        --output-dir outdir --only a --only b jobs.yaml
    check "a written under --output-dir" test -s outdir/out/a.exr
    check "nothing beside the manifest" test ! -e out
    check "a and b rendered 3 spp" test "$(grep -c '"event":"job_finished",.*"spp":3,' r0.jsonl)" -eq 2
    check_out "resume, same override" r1.jsonl "$CAVALRY_BATCH" --progress=json --resume --spp 3 \
        --output-dir outdir --only a --only b jobs.yaml
    check "both skipped" test "$(grep -c '"event":"job_skipped"' r1.jsonl)" -eq 2
    check_out "resume, other override" r2.jsonl "$CAVALRY_BATCH" --progress=json --resume --spp 2 \
        --output-dir outdir --only a --only b jobs.yaml
    check "both rendered again" test "$(grep -c '"event":"job_finished"' r2.jsonl)" -eq 2
    # b says spp: 2 in the manifest: without --spp it is the same render.
    check_out "resume, no override" r3.jsonl "$CAVALRY_BATCH" --progress=json --resume \
        --output-dir outdir --only a --only b jobs.yaml
    check "a rendered (4 spp), b skipped (its own 2)" sh -c \
        'grep -q "\"event\":\"job_finished\",.*\"job\":\"a\"" r3.jsonl && grep -q "\"event\":\"job_skipped\",.*\"job\":\"b\"" r3.jsonl'
    # An absolute --output-dir: the outputs, their locks and --resume under
    # it; an absolute output template outside the manifest's folder is kept.
    check_out "render --output-dir, absolute" abs.jsonl "$CAVALRY_BATCH" --progress=json \
        --output-dir "$tmp/abs" --only c jobs.yaml
    check "c written under the absolute folder" test -s "$tmp/abs/out/c.png"
    check "reported there" grep -qF "\"outputs\":[\"$tmp/abs/out/c.png\"]" abs.jsonl
    check "its lock beside it" test -e "$tmp/abs/out/.c.lock"
    check_out "resume, absolute --output-dir" abs2.jsonl "$CAVALRY_BATCH" --progress=json \
        --resume --output-dir "$tmp/abs" --only c jobs.yaml
    check "c skipped" grep -q '"event":"job_skipped",.*"job":"c"' abs2.jsonl
    mkdir sub
    printf 'version: 1\njobs:\n  - {name: k, scene: ../tiny.pbrt, spp: 1, formats: [png], output: "%s"}\n' \
        "$tmp/kept/{name}" >sub/kept.yaml
    check "render an absolute template with --output-dir" "$CAVALRY_BATCH" --progress=none \
        --output-dir "$tmp/abs" sub/kept.yaml
    check "the absolute template outside the manifest's folder is kept" \
        sh -c "test -s '$tmp/kept/k.png' && test -z \"\$(find '$tmp/abs' -name 'k.png')\""
    check "render from stdin" sh -c "\"$CAVALRY_BATCH\" -q --progress=none --only c - <jobs.yaml"
    check "stdin: output beside the working folder" test -s out/c.png
else
    echo "# no GPU context: rendering checks left out"
fi
done_testing
