#!/bin/sh
# out_of_memory_test.sh: exit status 70 (cavalry-batch(1), EXIT STATUS) is
# out of host memory. Under a 1 GiB address-space limit, a scene file
# whose size (2 GiB, sparse: no disk used) cannot be held fails the
# allocation that would read it: status 70, an "out of memory" error, and
# no image of any job, before or after it in the manifest.
. "${srcdir:-.}/tests/setup.sh"
cd "$tmp"
cp "$CV_TEST_DATA/batch/tiny.pbrt" .
cp tiny.pbrt big.pbrt
truncate -s 2G big.pbrt 2>/dev/null || skip_all "no truncate(1) or no sparse files"
cat >m.yaml <<'Y'
version: 1
defaults: {output: "out/{name}", spp: 1}
jobs:
  - name: a
    scene: tiny.pbrt
  - name: big
    scene: big.pbrt
Y
# A build whose start needs more address space (a sanitizer's shadow
# memory) cannot run under the limit at all.
(ulimit -v 1048576 && "$CAVALRY_BATCH" --version) >/dev/null 2>&1 ||
    skip_all "cavalry-batch does not start under a 1 GiB address-space limit"
(ulimit -v 1048576 && exec "$CAVALRY_BATCH" --progress=none m.yaml) >run.out 2>run.err &&
    rc=0 || rc=$?
check "out of host memory: exit status 70 (got $rc)" test "$rc" -eq 70
check "said" grep -q '^error: out of memory (asked for [0-9]* bytes)$' run.err
check "no image, no temporary file" test ! -e out
done_testing
