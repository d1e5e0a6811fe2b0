# tests/scene
check_PROGRAMS += tests/scene/dump_scene
tests_scene_dump_scene_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/scene/parse_test
TESTS += tests/scene/parse_test
tests_scene_parse_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/scene/scene_helpers.h
check_PROGRAMS += tests/scene/ply_test
TESTS += tests/scene/ply_test
tests_scene_ply_test_LDADD = $(CV_LIBS)
