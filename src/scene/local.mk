# src/scene: pbrt-v3/v4 scene import into the flat GPU scene.
libcavalry_a_SOURCES += \
	src/scene/scene.c src/scene/scene.h \
	src/scene/token.c src/scene/token.h \
	src/scene/params.c src/scene/params.h \
	src/scene/parse.c src/scene/parse.h \
	src/scene/builder.c src/scene/builder.h \
	src/scene/transform.c src/scene/transform.h \
	src/scene/animated.c src/scene/animated.h \
	src/scene/ply.c src/scene/ply.h \
	src/scene/shapes.c src/scene/curves.c \
	src/scene/materials.c \
	src/scene/bssrdf_table.c src/scene/bssrdf_table.h \
	src/scene/scattering_presets.c src/scene/scattering_presets.h \
	src/scene/coat_closed.c src/scene/coat_closed.h src/scene/fresnel.h \
	src/scene/spectrum.c src/scene/spectrum.h \
	src/scene/metal_spectra.c \
	src/scene/conductor_fresnel.c src/scene/conductor_fresnel.h \
	src/scene/rgl_tensor.c src/scene/rgl_tensor.h \
	src/scene/measured.c src/scene/measured.h \
	src/scene/image.c src/scene/image.h \
	src/scene/hdr_check.c src/scene/hdr_check.h \
	src/scene/exr_image.cpp src/scene/exr_image.h \
	src/scene/texture.c \
	src/scene/lights.c \
	src/scene/relight.c src/scene/relight.h \
	src/scene/env_file.c src/scene/env_file.h \
	src/scene/media.c \
	src/scene/media_grid.c \
	src/scene/media_cloud.c \
	src/scene/media_nanovdb.c \
	src/scene/nanovdb.c src/scene/nanovdb.h \
	src/scene/camera.c \
	src/scene/film.c src/scene/film.h \
	src/scene/filter.c src/scene/filter.h \
	src/scene/camera_matrix.c src/scene/camera_matrix.h \
	src/scene/dump.c src/scene/dump.h
