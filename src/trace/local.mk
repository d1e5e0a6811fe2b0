# src/trace: see Makefile.am
# ---- bsdf / light sampling (branch bsdf) ----
GLSL_FILES += \
	glsl/lib/constants.glsl glsl/lib/rng.glsl glsl/lib/frame.glsl glsl/lib/sampling.glsl \
	glsl/trace/bsdf/bsdf.glsl glsl/trace/bsdf/bsdf_sample.glsl glsl/trace/bsdf/material_buffers.glsl \
	glsl/trace/bsdf/fresnel.glsl glsl/trace/bsdf/microfacet.glsl glsl/trace/bsdf/diffuse.glsl \
	glsl/trace/bsdf/conductor.glsl glsl/trace/bsdf/dielectric.glsl glsl/trace/bsdf/coated.glsl \
	glsl/trace/bsdf/texture.glsl
libcavalry_a_SOURCES += src/trace/envmap_dist.c src/trace/envmap_dist.h
GLSL_FILES += glsl/shared/envmap.h glsl/trace/light/light.glsl glsl/trace/light/light_buffers.glsl \
	glsl/trace/light/envmap.glsl
# ---- end bsdf / light block ----
