# tests/base
check_PROGRAMS += tests/base/error_test
TESTS += tests/base/error_test
tests_base_error_test_LDADD = $(CV_LIBS)
