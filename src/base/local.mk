# src/base: errors, log, memory and file helpers used by every stage.
libcavalry_a_SOURCES += \
	src/base/clock.h \
	src/base/error.c src/base/error.h \
	src/base/file.c src/base/file.h \
	src/base/limits.h \
	src/base/log.c src/base/log.h \
	src/base/mem.c src/base/mem.h
