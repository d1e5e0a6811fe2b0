#!/bin/sh
# fuzz_manifest_test.sh: a short, fixed-seed run of the manifest fuzzer over
# the manifests of tests/data/manifest and tests/data/batch (see
# fuzz_manifest.c).
exec "$CV_TEST_BUILDDIR/manifest/fuzz_manifest" "${CV_FUZZ_ITERATIONS:-400}" 20261126 \
    "$CV_TEST_DATA/manifest" "$CV_TEST_DATA/batch"
