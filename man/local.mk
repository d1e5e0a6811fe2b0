# man/: manual pages, linted by tests/cli/help_man_test.sh and tests/manifest/man_lint_test.sh.
dist_man_MANS += man/cavalry-batch.1 man/cavalry-manifest.5
