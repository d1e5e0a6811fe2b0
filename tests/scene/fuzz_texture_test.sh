#!/bin/sh
# fuzz_texture_test.sh: a short, fixed-seed run of the texture fuzzer over
# the tiny images it writes and the PNG seeds of tests/data/trace/oracle
# (see fuzz_texture.c).
exec "$CV_TEST_BUILDDIR/scene/fuzz_texture" "${CV_FUZZ_ITERATIONS:-400}" 20261126 \
    "$CV_TEST_DATA/trace/oracle"
