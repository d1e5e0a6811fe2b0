# tests/scene
check_PROGRAMS += tests/scene/dump_scene
tests_scene_dump_scene_LDADD = $(CV_LIBS)
