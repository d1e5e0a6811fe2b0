# src/color: OpenColorIO display transforms on the GPU.
libcavalry_a_SOURCES += \
	src/color/color.h src/color/color_params.h src/color/color_pass.c \
	src/color/ocio.h src/color/ocio_shim.cpp \
	src/color/ocio_spaces.cpp src/color/ocio_spaces.hpp src/color/display_encoding.h
nodist_libcavalry_a_SOURCES += src/color/ocio_config_embedded.c
EXTRA_DIST += src/color/embed_config.sh
GLSL_FILES += glsl/color/display.comp glsl/color/lut_filter.glsl

src/color/ocio_config_embedded.c: $(srcdir)/configs/cavalry.ocio $(srcdir)/src/color/embed_config.sh
	$(AM_V_GEN)$(MKDIR_P) src/color && \
	$(SHELL) $(srcdir)/src/color/embed_config.sh $(srcdir)/configs/cavalry.ocio >$@.tmp && mv $@.tmp $@
BUILT_SOURCES += src/color/ocio_config_embedded.c
CLEANFILES += src/color/ocio_config_embedded.c
