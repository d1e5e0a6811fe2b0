# tests/trace: see tests/local.mk
# --- pipeline tests (the BSDF helper keeps its bsdf_*/light_* lines in a separate block) ---
check_PROGRAMS += tests/trace/analytic_test
TESTS += tests/trace/analytic_test
tests_trace_analytic_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/trace/trace_test_util.h \
	tests/data/trace/make_scenes.py tests/data/trace/analytic.pbrt \
	tests/data/trace/furnace.pbrt tests/data/trace/quad.pbrt
# --- end of pipeline tests ---
# --- rlpath tests (reinforcement-learning path guiding) ---
check_PROGRAMS += tests/trace/rlpath_sample_test
TESTS += tests/trace/rlpath_sample_test
tests_trace_rlpath_sample_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/trace/rlpath_stats.h
# --- end of rlpath tests ---
# --- rlpath tests, part 2 ---
check_PROGRAMS += tests/trace/rlpath_converge_test
TESTS += tests/trace/rlpath_converge_test
tests_trace_rlpath_converge_test_LDADD = $(CV_LIBS)
# --- end of rlpath tests, part 2 ---
# --- rlpath benchmark (not a test: `make tests/trace/rlpath_bench`) ---
EXTRA_PROGRAMS = tests/trace/rlpath_bench
tests_trace_rlpath_bench_LDADD = $(CV_LIBS)
CLEANFILES += tests/trace/rlpath_bench
# --- end of rlpath benchmark ---
