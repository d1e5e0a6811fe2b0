# src/cli: command line of cavalry-batch.
src_cavalry_batch_SOURCES += src/cli/main.c
libcavalry_a_SOURCES += src/cli/cli.c src/cli/cli.h src/cli/exit_codes.h \
	src/cli/knobs.c src/cli/knobs.h
