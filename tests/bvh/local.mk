# tests/bvh: GPU radix sort, tree invariants and SAH quality, traversal
# against brute force; bvh_bench is built with `make check` but not run.
check_PROGRAMS += tests/bvh/radix_sort_test tests/bvh/bvh_test tests/bvh/bvh_bench
TESTS += tests/bvh/radix_sort_test tests/bvh/bvh_test
tests_bvh_radix_sort_test_LDADD = $(CV_LIBS)
tests_bvh_bvh_test_SOURCES = tests/bvh/bvh_test.c tests/bvh/bvh_test_util.h tests/bvh/sah_ref.h \
	tests/bvh/widen_ref.h
tests_bvh_bvh_test_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/glsl
tests_bvh_bvh_test_LDADD = $(CV_LIBS)
tests_bvh_bvh_bench_SOURCES = tests/bvh/bvh_bench.c tests/bvh/bvh_test_util.h tests/bvh/sah_ref.h \
	tests/bvh/widen_ref.h
tests_bvh_bvh_bench_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/glsl
tests_bvh_bvh_bench_LDADD = $(CV_LIBS)
# curve shapes: tree walk against brute force, straight curves, conversions
check_PROGRAMS += tests/bvh/motion_test
TESTS += tests/bvh/motion_test
tests_bvh_motion_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/bvh/curves_test
TESTS += tests/bvh/curves_test
tests_bvh_curves_test_LDADD = $(CV_LIBS)
