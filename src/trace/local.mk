# src/trace: the wavefront path tracer (host side; shaders in glsl/trace).
libcavalry_a_SOURCES += \
	src/trace/filter_table.c src/trace/filter_table.h \
	src/trace/camera_motion.c src/trace/camera_motion.h \
	src/trace/integrator.c src/trace/integrator.h \
	src/trace/bdpt.c src/trace/bdpt.h \
	src/trace/render.c src/trace/render.h src/trace/scene_defines.h \
	src/trace/scene_upload.c src/trace/scene_upload.h \
	src/trace/shade_bins.c src/trace/shade_bins.h \
	src/trace/sdtree.c src/trace/sdtree.h \
	src/trace/rlpath_sd.c src/trace/rlpath_sd.h \
	src/trace/guide_choice.c src/trace/guide_choice.h

GLSL_FILES += \
	glsl/shared/trace.h \
	glsl/trace/common.glsl glsl/trace/sampler.glsl glsl/trace/camera.glsl glsl/trace/filter.glsl \
	glsl/trace/geometry.glsl glsl/trace/tracing.glsl \
	glsl/trace/materials.glsl glsl/trace/bsdf_basic.glsl glsl/trace/lights.glsl glsl/trace/scene_buffers.glsl \
	glsl/trace/surface_inputs.glsl glsl/trace/path_vertex.glsl glsl/trace/shade_queue.glsl \
	glsl/trace/unroll_hint.glsl \
	glsl/trace/generate.comp glsl/trace/intersect.comp glsl/trace/queue_args.glsl \
	glsl/trace/regenerate.glsl \
	glsl/trace/escaped.comp glsl/trace/shade.comp glsl/trace/shadow.comp \
	glsl/trace/resolve.comp glsl/trace/matte.comp glsl/trace/test/sampler_probe.comp \
	glsl/trace/test/trace_probe.comp \
	glsl/shared/guide_choice.h glsl/trace/guide_choice.comp \
	glsl/shared/bdpt.h glsl/trace/bdpt/bdpt.comp glsl/trace/bdpt/endpoints.glsl \
	glsl/trace/bdpt/media.glsl
# ---- bsdf / light sampling (branch bsdf) ----
GLSL_FILES += \
	glsl/lib/constants.glsl glsl/lib/rng.glsl glsl/lib/frame.glsl glsl/lib/sampling.glsl \
	glsl/lib/quaternion.glsl glsl/trace/path_time.glsl \
	glsl/trace/bsdf/bsdf.glsl glsl/trace/bsdf/bsdf_sample.glsl glsl/trace/bsdf/material_buffers.glsl \
	glsl/trace/bsdf/texture_buffers.glsl \
	glsl/trace/bsdf/fresnel.glsl glsl/trace/bsdf/microfacet.glsl glsl/trace/bsdf/diffuse.glsl \
	glsl/trace/bsdf/conductor.glsl glsl/trace/bsdf/dielectric.glsl glsl/trace/bsdf/layered.glsl \
	glsl/trace/bsdf/coated_closed.glsl \
	glsl/trace/bsdf/plastic.glsl glsl/trace/bsdf/texture.glsl glsl/trace/bsdf/alpha.glsl
libcavalry_a_SOURCES += src/trace/envmap_dist.c src/trace/envmap_dist.h
GLSL_FILES += glsl/shared/envmap.h glsl/trace/light/light.glsl glsl/trace/light/light_buffers.glsl \
	glsl/trace/light/envmap.glsl
# ---- end bsdf / light block ----

# --- rlpath (reinforcement-learning path guiding) ---
libcavalry_a_SOURCES += src/trace/rlpath.c src/trace/rlpath.h
GLSL_FILES += glsl/shared/rlpath.h \
	glsl/trace/rlpath/guide.glsl glsl/trace/rlpath/shade.comp \
	glsl/trace/rlpath/test_sample.comp \
	glsl/trace/rlpath/rebuild.comp \
	glsl/shared/sdtree.h glsl/trace/rlpath/sdtree.glsl glsl/trace/rlpath/sd_shade.comp \
	glsl/trace/rlpath/guides.glsl glsl/trace/rlpath/sd_flush.comp \
	glsl/trace/rlpath/test_sd_sample.comp
# --- end of rlpath ---
# --- hair BSDF and curves (issue 27 item 2) ---
GLSL_FILES += glsl/trace/bsdf/hair.glsl glsl/bvh/curves.glsl
# --- measured BRDFs (issue 27 item 4) ---
GLSL_FILES += glsl/shared/measured.h glsl/trace/bsdf/measured.glsl

# --- participating media (volpath) ---
GLSL_FILES += glsl/shared/medium.h glsl/trace/medium/medium.glsl glsl/trace/medium/track.glsl \
	glsl/trace/medium/random.glsl \
	glsl/trace/medium/vertex.glsl glsl/trace/test/phase_probe.comp \
	glsl/trace/medium/grid.glsl glsl/trace/test/grid_probe.comp
# pbrt-v4's cloud medium and the Perlin noise it is made of
GLSL_FILES += glsl/shared/perlin.h glsl/lib/noise.glsl glsl/trace/medium/cloud.glsl
# --- end of participating media ---

# --- subsurface material (issue 27 item 4) ---
GLSL_FILES += glsl/shared/bssrdf.h glsl/trace/bsdf/bssrdf.glsl glsl/trace/bsdf/sss_exit.glsl \
	glsl/trace/sss_probe.glsl glsl/trace/sss_vertex.glsl glsl/trace/test/bssrdf_probe.comp
# --- end of subsurface ---
# --- conductors given by spectra: Fresnel tables (issue 24) ---
GLSL_FILES += glsl/shared/conductor_fresnel.h
# --- the one BSDF query (issue 26) ---
GLSL_FILES += glsl/trace/bsdf/bsdf_query.glsl glsl/shared/bsdf_query.h
# --- a camera ray's first hit for the mattes, shared by matte.comp and bdpt (issue 27) ---
GLSL_FILES += glsl/trace/matte.glsl
