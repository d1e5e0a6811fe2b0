# tests/trace
# ---- bsdf / light sampling tests (branch bsdf) ----
check_PROGRAMS += tests/trace/bsdf_chi2_test
TESTS += tests/trace/bsdf_chi2_test
tests_trace_bsdf_chi2_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/bsdf_energy_test
TESTS += tests/trace/bsdf_energy_test
tests_trace_bsdf_energy_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/bsdf_material_test
TESTS += tests/trace/bsdf_material_test
tests_trace_bsdf_material_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/light_sampling_test
TESTS += tests/trace/light_sampling_test
tests_trace_light_sampling_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/trace/bsdf_probe.h tests/trace/bsdf_stats.h \
	glsl/trace/test/light_probe.comp \
	glsl/trace/test/shade_compile.comp \
	glsl/trace/test/bsdf_probe.comp
# ---- end bsdf / light block ----
