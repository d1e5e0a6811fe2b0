# man/: manual pages, linted by tests/cli/man_test.sh.
dist_man_MANS += man/cavalry-batch.1
