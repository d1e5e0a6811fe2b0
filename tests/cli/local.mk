# tests/cli
TESTS += tests/cli/help_man_test.sh tests/cli/dist_test.sh tests/cli/overrides_test.sh
EXTRA_DIST += tests/cli/help_man_test.sh tests/cli/dist_test.sh tests/cli/overrides_test.sh
check_PROGRAMS += tests/cli/knobs_test
TESTS += tests/cli/knobs_test
tests_cli_knobs_test_LDADD = $(CV_LIBS)
