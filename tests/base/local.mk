# tests/base
check_PROGRAMS += tests/base/error_test
TESTS += tests/base/error_test
tests_base_error_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/base/mem_test
TESTS += tests/base/mem_test
tests_base_mem_test_LDADD = $(CV_LIBS)
