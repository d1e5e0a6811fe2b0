# src/output: atomic image files, OpenEXR (scene-linear) and PNG (display-referred).
libcavalry_a_SOURCES += \
	src/output/atomic_file.c src/output/atomic_file.h \
	src/output/metadata.c src/output/metadata.h \
	src/output/exr_write.c src/output/exr_write.h \
	src/output/exr_read.c src/output/exr_read.h \
	src/output/exr_merge.c src/output/exr_merge.h \
	src/output/png_write.c src/output/png_write.h \
	src/output/png_read.c src/output/png_read.h \
	src/output/cryptomatte.c src/output/cryptomatte.h
