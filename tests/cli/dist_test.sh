#!/bin/sh
# dist_test.sh: what a release tarball needs, checked in the tree the tests
# run from (under make distcheck, the unpacked tarball): the MIT licence and
# a README that names it, and shell tests that find the programs they run
# in the build tree (CV_TEST_BUILDDIR, CAVALRY_BATCH), never beside their
# own script, which is in the source tree.
. "${srcdir:-.}/tests/setup.sh"
top=$CAVALRY_DATA_DIR
check "LICENSE is there" test -s "$top/LICENSE"
check "LICENSE is the MIT licence" grep -q '^MIT License$' "$top/LICENSE"
check "LICENSE names the copyright holders" grep -q 'Copyright (c) The Cavalry authors' "$top/LICENSE"
check "README.md is there" test -s "$top/README.md"
check "README.md names the licence" grep -q 'MIT licence' "$top/README.md"
# A built helper is found through the test environment, not "$(dirname "$0")".
found=$(cd "$top" && grep -l 'dirname "\$0"' tests/*/*.sh 2>/dev/null | grep -v /dist_test.sh || true)
check "no test looks for programs beside its own script (${found:-none})" test -z "$found"
done_testing
