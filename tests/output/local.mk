# tests/output: atomic writes, EXR and PNG written and read back.
EXTRA_DIST += tests/output/output_helpers.h
check_PROGRAMS += tests/output/atomic_file_test tests/output/metadata_test \
	tests/output/exr_write_test tests/output/png_write_test
TESTS += tests/output/atomic_file_test tests/output/metadata_test \
	tests/output/exr_write_test tests/output/png_write_test
tests_output_atomic_file_test_LDADD = $(CV_LIBS)
tests_output_metadata_test_LDADD = $(CV_LIBS)
tests_output_exr_write_test_LDADD = $(CV_LIBS)
tests_output_png_write_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/output/png_read_test
TESTS += tests/output/png_read_test
tests_output_png_read_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/output/exr_read_test
TESTS += tests/output/exr_read_test
tests_output_exr_read_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/output/cryptomatte_test
TESTS += tests/output/cryptomatte_test
tests_output_cryptomatte_test_LDADD = $(CV_LIBS)
