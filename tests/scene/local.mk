# tests/scene: the pbrt importer. dump_scene prints cv_scene_dump for the
# shell tests; fuzz_scene and fuzz_texture are the mutation fuzzers run by
# fuzz_test.sh and fuzz_texture_test.sh.
check_PROGRAMS += tests/scene/dump_scene tests/scene/fuzz_scene tests/scene/fuzz_texture
tests_scene_dump_scene_LDADD = $(CV_LIBS)
tests_scene_fuzz_scene_LDADD = $(CV_LIBS)
tests_scene_fuzz_texture_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/scene/parse_test
TESTS += tests/scene/parse_test
tests_scene_parse_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/scene/nanovdb_test
TESTS += tests/scene/nanovdb_test
tests_scene_nanovdb_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/scene/camera_matrix_test
TESTS += tests/scene/camera_matrix_test
tests_scene_camera_matrix_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/scene/animated_test
TESTS += tests/scene/animated_test
tests_scene_animated_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/scene/ply_test
TESTS += tests/scene/ply_test
tests_scene_ply_test_LDADD = $(CV_LIBS)

TESTS += tests/scene/fuzz_test.sh tests/scene/fuzz_texture_test.sh tests/scene/shared_scenes_test.sh tests/scene/inputs_test.sh
EXTRA_DIST += tests/scene/scene_helpers.h tests/scene/fuzz_test.sh tests/scene/fuzz_texture_test.sh tests/scene/shared_scenes_test.sh \
	tests/scene/inputs_test.sh \
	tests/data/scene/tiny-v3.pbrt tests/data/scene/tiny-v4.pbrt tests/data/scene/errors.pbrt \
	tests/data/scene/quad.ply tests/data/scene/quad-be.ply tests/data/scene/quad-le.ply

check_PROGRAMS += tests/scene/hdr_check_test
TESTS += tests/scene/hdr_check_test
tests_scene_hdr_check_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/scene/bssrdf_table_test
TESTS += tests/scene/bssrdf_table_test
tests_scene_bssrdf_table_test_LDADD = $(CV_LIBS)
# --- measured BRDFs (issue 27 item 4): RGL tensor files ---
check_PROGRAMS += tests/scene/rgl_tensor_test
TESTS += tests/scene/rgl_tensor_test
tests_scene_rgl_tensor_test_LDADD = $(CV_LIBS)

# --- conductors given by spectra: Fresnel tables (issue 24) ---
check_PROGRAMS += tests/scene/conductor_fresnel_test
TESTS += tests/scene/conductor_fresnel_test
tests_scene_conductor_fresnel_test_LDADD = $(CV_LIBS)
