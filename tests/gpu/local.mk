# tests/gpu
check_PROGRAMS += tests/gpu/compute_test tests/gpu/compute_osmesa_test tests/gpu/program_test \
	tests/gpu/program_cache_test tests/gpu/buffer_pool_test tests/gpu/storage_test tests/gpu/timer_test \
	tests/gpu/buf_test tests/gpu/embedded_glsl_text_test
TESTS += tests/gpu/compute_test tests/gpu/compute_osmesa_test tests/gpu/program_test tests/gpu/program_cache_test \
	tests/gpu/buffer_pool_test tests/gpu/storage_test tests/gpu/timer_test tests/gpu/buf_test \
	tests/gpu/embedded_glsl_text_test \
	tests/gpu/list_gpus_test.sh tests/gpu/embedded_glsl_test.sh tests/gpu/bindings_test.sh
tests_gpu_compute_test_LDADD = $(CV_LIBS)
tests_gpu_compute_osmesa_test_SOURCES = tests/gpu/compute_test.c
tests_gpu_compute_osmesa_test_CPPFLAGS = $(AM_CPPFLAGS) -DCV_TEST_OSMESA
tests_gpu_compute_osmesa_test_LDADD = $(CV_LIBS)
tests_gpu_program_test_LDADD = $(CV_LIBS)
tests_gpu_program_cache_test_LDADD = $(CV_LIBS)
tests_gpu_buffer_pool_test_LDADD = $(CV_LIBS)
tests_gpu_storage_test_LDADD = $(CV_LIBS)
tests_gpu_timer_test_LDADD = $(CV_LIBS)
tests_gpu_buf_test_LDADD = $(CV_LIBS)
tests_gpu_embedded_glsl_text_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/gpu/gpu_test_util.h tests/gpu/probe.h tests/gpu/list_gpus_test.sh tests/gpu/embedded_glsl_test.sh \
	tests/gpu/bindings_test.sh \
	tests/data/gpu/glsl/broken.comp tests/data/gpu/glsl/inc/fine.glsl tests/data/gpu/glsl/inc/bad.glsl \
	tests/data/gpu/glsl/good.comp tests/data/gpu/glsl/continued.comp \
	tests/data/gpu/glsl/inc/continued.glsl
