# src/gpu: headless context, GLSL loader, buffers.
libcavalry_a_SOURCES += \
	src/gpu/buffer.c src/gpu/buffer.h \
	src/gpu/buffer_pool.c src/gpu/buffer_pool.h \
	src/gpu/context.c src/gpu/context.h src/gpu/context_platform.h \
	src/gpu/context_egl.c src/gpu/context_osmesa.c \
	src/gpu/gl_check.c src/gpu/gl_check.h \
	src/gpu/memory.c src/gpu/memory.h \
	src/gpu/storage.c src/gpu/storage.h \
	src/gpu/glsl_source.c src/gpu/glsl_source.h \
	src/gpu/program.c src/gpu/program.h \
	src/gpu/program_disk_cache.c src/gpu/program_disk_cache.h \
	src/gpu/timer.c src/gpu/timer.h \
	src/gpu/buf.c src/gpu/buf.h
nodist_libcavalry_a_SOURCES = src/gpu/glsl_embedded.c
EXTRA_DIST += src/gpu/embed_glsl.sh src/gpu/gl_functions.sh $(GLSL_FILES)

# Every file under glsl/ that the binary carries; stages add theirs.
GLSL_FILES += \
	glsl/shared/common.h glsl/shared/scene.h glsl/shared/bindings.h \
	glsl/lib/index.glsl glsl/lib/atomic_add.glsl \
	glsl/gpu/selftest.comp glsl/gpu/storage_probe.comp

# Makefile too: adding a file to GLSL_FILES must regenerate the list.
src/gpu/glsl_embedded.c: $(GLSL_FILES) $(srcdir)/src/gpu/embed_glsl.sh Makefile
	$(AM_V_GEN)$(MKDIR_P) src/gpu && \
	$(SHELL) $(srcdir)/src/gpu/embed_glsl.sh $(srcdir) $(GLSL_FILES) >$@.tmp && mv $@.tmp $@

# The GL functions the C sources call, for the OSMesa dispatch table.
# Tests call GL too and may run under OSMesa, so they are scanned as well.
GL_SCANNED = $(wildcard $(srcdir)/src/*/*.c $(srcdir)/tests/*/*.c)
src/gpu/gl_functions.h: $(GL_SCANNED) $(srcdir)/src/gpu/gl_functions.sh
	$(AM_V_GEN)$(MKDIR_P) src/gpu && \
	$(SHELL) $(srcdir)/src/gpu/gl_functions.sh $(GL_SCANNED) >$@.tmp && mv $@.tmp $@
BUILT_SOURCES += src/gpu/gl_functions.h src/gpu/glsl_embedded.c
# BUILT_SOURCES is made first only by `make all`, `check` and `install`; a
# named target (`make src/cavalry-batch`) needs the dependency spelled out,
# as automake's dependency tracking knows the header only after a first
# compile.
src/gpu/context_osmesa.$(OBJEXT): src/gpu/gl_functions.h
CLEANFILES += src/gpu/gl_functions.h src/gpu/glsl_embedded.c
