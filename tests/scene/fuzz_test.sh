#!/bin/sh
# fuzz_test.sh: a short, fixed-seed run of the scene/PLY fuzzer over the
# seed corpus in tests/data/scene (see fuzz_scene.c).
exec "$CV_TEST_BUILDDIR/scene/fuzz_scene" "$CV_TEST_DATA/scene" "${CV_FUZZ_ITERATIONS:-3000}" 20261122
