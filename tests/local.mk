# tests/: one local.mk per stage, mirroring src/.
EXTRA_DIST += tests/tap.h tests/rng.h tests/fuzz_mutate.h tests/setup.sh tests/lsan.supp
include tests/base/local.mk
include tests/manifest/local.mk
include tests/scene/local.mk
include tests/gpu/local.mk
include tests/bvh/local.mk
include tests/trace/local.mk
include tests/color/local.mk
include tests/output/local.mk
include tests/batch/local.mk
include tests/cli/local.mk
include tests/contrib/local.mk
