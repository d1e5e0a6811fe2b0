# tests/cli
TESTS += tests/cli/help_man_test.sh tests/cli/dist_test.sh
EXTRA_DIST += tests/cli/help_man_test.sh tests/cli/dist_test.sh
