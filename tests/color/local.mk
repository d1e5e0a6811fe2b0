# tests/color
check_PROGRAMS += tests/color/color_gpu_test tests/color/ocio_test
TESTS += tests/color/color_gpu_test tests/color/ocio_test
tests_color_color_gpu_test_LDADD = $(CV_LIBS)
tests_color_ocio_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/data/color/lut_look.ocio tests/data/color/warm.cube \
	tests/data/color/curve.spi1d tests/data/color/small.spi1d tests/data/color/broken.ocio
# --- configs whose scene_linear is not linear Rec.709 (issue 24, bug 7) ---
check_PROGRAMS += tests/color/ocio_spaces_test
TESTS += tests/color/ocio_spaces_test
tests_color_ocio_spaces_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/data/color/acescg.ocio tests/data/color/misnamed.ocio \
	tests/data/color/unplaced.ocio
