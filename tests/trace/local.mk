# tests/trace: see tests/local.mk
# --- pipeline tests (the BSDF helper keeps its bsdf_*/light_* lines in a separate block) ---
check_PROGRAMS += tests/trace/analytic_test tests/trace/furnace_test tests/trace/passes_test \
	tests/trace/cornell_test tests/trace/sampler_test tests/trace/filter_table_test
TESTS += tests/trace/analytic_test tests/trace/furnace_test tests/trace/passes_test \
	tests/trace/cornell_test tests/trace/sampler_test tests/trace/filter_table_test
tests_trace_analytic_test_LDADD = $(CV_LIBS)
tests_trace_furnace_test_LDADD = $(CV_LIBS)
tests_trace_passes_test_LDADD = $(CV_LIBS)
tests_trace_cornell_test_LDADD = $(CV_LIBS)
tests_trace_sampler_test_LDADD = $(CV_LIBS)
tests_trace_filter_table_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/trace/trace_test_util.h tests/trace/exr_ref.h tests/trace/rlpath_room.h \
	tests/data/trace/make_scenes.py tests/data/trace/analytic.pbrt \
	tests/data/trace/furnace.pbrt tests/data/trace/quad.pbrt
# --- light and ray-offset tests (branch lightfix) ---
check_PROGRAMS += tests/trace/env_plane_test tests/trace/envmap_wrap_test
TESTS += tests/trace/env_plane_test tests/trace/envmap_wrap_test
tests_trace_env_plane_test_LDADD = $(CV_LIBS)
tests_trace_envmap_wrap_test_LDADD = $(CV_LIBS)
# --- end of light and ray-offset tests ---
# --- end of pipeline tests ---
# ---- bsdf / light sampling tests (branch bsdf) ----
check_PROGRAMS += tests/trace/bsdf_chi2_test
TESTS += tests/trace/bsdf_chi2_test
tests_trace_bsdf_chi2_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/bsdf_energy_test
TESTS += tests/trace/bsdf_energy_test
tests_trace_bsdf_energy_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/bsdf_layered_test
TESTS += tests/trace/bsdf_layered_test
tests_trace_bsdf_layered_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/bsdf_query_test
TESTS += tests/trace/bsdf_query_test
tests_trace_bsdf_query_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/bsdf_coat_closed_test
TESTS += tests/trace/bsdf_coat_closed_test
tests_trace_bsdf_coat_closed_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/bsdf_material_test
TESTS += tests/trace/bsdf_material_test
tests_trace_bsdf_material_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/texture_tree_test
TESTS += tests/trace/texture_tree_test
tests_trace_texture_tree_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/light_sampling_test
TESTS += tests/trace/light_sampling_test
tests_trace_light_sampling_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/trace/grid_probe.h \
	tests/trace/bsdf_probe.h tests/trace/bsdf_stats.h tests/trace/fresnel_ref.h \
	glsl/trace/test/light_probe.comp \
	glsl/trace/test/shade_compile.comp \
	glsl/trace/test/bsdf_probe.comp
# ---- end bsdf / light block ----
# --- rlpath tests (reinforcement-learning path guiding) ---
check_PROGRAMS += tests/trace/rlpath_sample_test tests/trace/rlpath_converge_test \
	tests/trace/rlpath_mix_test tests/trace/misses_test
TESTS += tests/trace/rlpath_sample_test tests/trace/rlpath_converge_test tests/trace/rlpath_mix_test \
	tests/trace/misses_test
tests_trace_misses_test_LDADD = $(CV_LIBS)
tests_trace_rlpath_sample_test_LDADD = $(CV_LIBS)
tests_trace_rlpath_converge_test_LDADD = $(CV_LIBS)
tests_trace_rlpath_mix_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/trace/rlpath_stats.h
# the benchmark is not a test: `make tests/trace/rlpath_bench`
EXTRA_PROGRAMS = tests/trace/rlpath_bench
tests_trace_rlpath_bench_LDADD = $(CV_LIBS)
CLEANFILES += tests/trace/rlpath_bench
# rlpath's sdtree method (Müller et al.'s guide)
check_PROGRAMS += tests/trace/sdtree_test tests/trace/rlpath_sd_sample_test \
	tests/trace/rlpath_sd_splat_test
TESTS += tests/trace/sdtree_test tests/trace/rlpath_sd_sample_test \
	tests/trace/rlpath_sd_splat_test
tests_trace_sdtree_test_LDADD = $(CV_LIBS)
tests_trace_rlpath_sd_sample_test_LDADD = $(CV_LIBS)
tests_trace_rlpath_sd_splat_test_LDADD = $(CV_LIBS)
# the programs of its passes after training
check_PROGRAMS += tests/trace/rlpath_frozen_test
TESTS += tests/trace/rlpath_frozen_test
tests_trace_rlpath_frozen_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/rlpath_unguided_test
TESTS += tests/trace/rlpath_unguided_test
tests_trace_rlpath_unguided_test_LDADD = $(CV_LIBS)
# the guide's choice after training
check_PROGRAMS += tests/trace/guide_choice_test
TESTS += tests/trace/guide_choice_test
tests_trace_guide_choice_test_LDADD = $(CV_LIBS)
# --- end of rlpath tests ---
# --- HDR textures in float (issue 24, bug 5) ---
check_PROGRAMS += tests/trace/hdr_envmap_test
TESTS += tests/trace/hdr_envmap_test
tests_trace_hdr_envmap_test_LDADD = $(CV_LIBS)
# --- pbrt-v4's spherical camera, pbrt-v3's environment camera ---
check_PROGRAMS += tests/trace/spherical_camera_test
TESTS += tests/trace/spherical_camera_test
tests_trace_spherical_camera_test_LDADD = $(CV_LIBS)
# --- cut-out emitters masked as pbrt-v4 masks them ---
check_PROGRAMS += tests/trace/alpha_emitter_test
TESTS += tests/trace/alpha_emitter_test
tests_trace_alpha_emitter_test_LDADD = $(CV_LIBS)
# --- next-event estimation off against on; BSDFs with a delta lobe ---
check_PROGRAMS += tests/trace/nee_test tests/trace/bsdf_delta_test
TESTS += tests/trace/nee_test tests/trace/bsdf_delta_test
tests_trace_nee_test_LDADD = $(CV_LIBS)
tests_trace_bsdf_delta_test_LDADD = $(CV_LIBS)
# --- end of nee / delta tests ---
# --- oracle tests: pbrt-v4 references (tests/data/trace/oracle/README) ---
check_PROGRAMS += tests/trace/oracle_test
TESTS += tests/trace/oracle_test
tests_trace_oracle_test_LDADD = $(CV_LIBS)
# scenes (nee_test's too), their pbrt-v4 references and the generator
EXTRA_DIST += tests/data/trace/oracle
# --- end of oracle tests ---
# --- pixel filters and camera (branch filmcam) ---
check_PROGRAMS += tests/trace/filter_sample_test tests/trace/camera_motion_test
TESTS += tests/trace/filter_sample_test tests/trace/camera_motion_test
tests_trace_filter_sample_test_LDADD = $(CV_LIBS)
tests_trace_camera_motion_test_LDADD = $(CV_LIBS)
EXTRA_DIST += glsl/trace/test/filter_probe.comp
# --- end of pixel filters and camera ---
# --- hair BSDF and curves (issue 27 item 2) ---
check_PROGRAMS += tests/trace/bsdf_hair_test
TESTS += tests/trace/bsdf_hair_test
tests_trace_bsdf_hair_test_LDADD = $(CV_LIBS)
# --- end of hair and curves ---
# --- participating media (volpath; glsl/trace/medium) ---
check_PROGRAMS += tests/trace/medium_furnace_test
TESTS += tests/trace/medium_furnace_test
tests_trace_medium_furnace_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/medium_phase_test
TESTS += tests/trace/medium_phase_test
tests_trace_medium_phase_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/medium_grid_test
TESTS += tests/trace/medium_grid_test
tests_trace_medium_grid_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/medium_cloud_test
TESTS += tests/trace/medium_cloud_test
tests_trace_medium_cloud_test_LDADD = $(CV_LIBS)
check_PROGRAMS += tests/trace/medium_nanovdb_test
TESTS += tests/trace/medium_nanovdb_test
tests_trace_medium_nanovdb_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/data/trace/medium_furnace.pbrt
# --- end of participating media ---

check_PROGRAMS += tests/trace/bssrdf_sample_test
TESTS += tests/trace/bssrdf_sample_test
tests_trace_bssrdf_sample_test_LDADD = $(CV_LIBS)
# --- shade bins (issue 26) ---
check_PROGRAMS += tests/trace/shade_bins_test
TESTS += tests/trace/shade_bins_test
tests_trace_shade_bins_test_LDADD = $(CV_LIBS)
# the coated walk inlined once per kernel
check_PROGRAMS += tests/trace/bsdf_sites_test
TESTS += tests/trace/bsdf_sites_test
tests_trace_bsdf_sites_test_LDADD = $(CV_LIBS)
# --- measured BRDFs (issue 27 item 4) ---
check_PROGRAMS += tests/trace/bsdf_measured_test
TESTS += tests/trace/bsdf_measured_test
tests_trace_bsdf_measured_test_LDADD = $(CV_LIBS)
# --- end of measured BRDFs ---
# --- bidirectional path tracing (bdpt; glsl/trace/bdpt) ---
check_PROGRAMS += tests/trace/bdpt_test
TESTS += tests/trace/bdpt_test
tests_trace_bdpt_test_LDADD = $(CV_LIBS)
# --- end of bdpt ---
# --- every feature in one scene: all kernels link (storage block limits) ---
check_PROGRAMS += tests/trace/all_features_test
TESTS += tests/trace/all_features_test
tests_trace_all_features_test_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/data/trace/all_features.pbrt

# --- conductors given by spectra: Fresnel tables in the GLSL (issue 24) ---
check_PROGRAMS += tests/trace/bsdf_conductor_fresnel_test
TESTS += tests/trace/bsdf_conductor_fresnel_test
tests_trace_bsdf_conductor_fresnel_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/trace/medium_grid_store_test
TESTS += tests/trace/medium_grid_store_test
tests_trace_medium_grid_store_test_LDADD = $(CV_LIBS)

check_PROGRAMS += tests/trace/sdtree_filter_test
TESTS += tests/trace/sdtree_filter_test
tests_trace_sdtree_filter_test_LDADD = $(CV_LIBS)
