# tests/batch
check_PROGRAMS += tests/batch/exr_attr tests/batch/exr_same tests/batch/plan_test \
	tests/batch/exr_probe tests/batch/pass_size_test
tests_batch_pass_size_test_LDADD = $(CV_LIBS)
tests_batch_exr_probe_LDADD = $(CV_LIBS)
tests_batch_plan_test_LDADD = $(CV_LIBS)
tests_batch_exr_attr_LDADD = $(CV_LIBS)
tests_batch_exr_same_LDADD = $(CV_LIBS)
TESTS += tests/batch/plan_test tests/batch/pass_size_test tests/batch/check_plan_test.sh tests/batch/manifest_errors_test.sh \
	tests/batch/shard_test.sh tests/batch/render_test.sh tests/batch/signals_test.sh \
	tests/batch/shared_scene_test.sh tests/batch/lock_test.sh tests/batch/check_all_test.sh \
	tests/batch/man_examples_test.sh tests/batch/resume_stale_test.sh tests/batch/tiles_test.sh \
	tests/batch/progress_test.sh
EXTRA_DIST += tests/batch/check_plan_test.sh tests/batch/manifest_errors_test.sh tests/batch/shard_test.sh \
	tests/batch/render_test.sh tests/batch/signals_test.sh tests/batch/shared_scene_test.sh \
	tests/batch/lock_test.sh tests/batch/check_all_test.sh tests/batch/man_examples_test.sh \
	tests/batch/resume_stale_test.sh tests/batch/tiles_test.sh tests/data/batch/tiles.yaml \
	tests/data/batch/tiles.pbrt tests/batch/progress_test.sh tests/batch/progress_check.py \
	tests/data/batch/tiny.pbrt tests/data/batch/broken.pbrt tests/data/batch/jobs.yaml \
	tests/data/batch/many.yaml tests/data/batch/long.yaml
# --- PNG colour tags by display encoding (issue 24, bug 7) ---
TESTS += tests/batch/png_tag_test.sh
EXTRA_DIST += tests/batch/png_tag_test.sh
# --- multi-GPU batches: --gpu all, --workers (issue 28) ---
TESTS += tests/batch/workers_test.sh
EXTRA_DIST += tests/batch/workers_test.sh
# --- matrix jobs and light overrides (issue 28) ---
check_PROGRAMS += tests/batch/exr_scale
tests_batch_exr_scale_LDADD = $(CV_LIBS)
TESTS += tests/batch/matrix_test.sh tests/batch/relight_test.sh
EXTRA_DIST += tests/batch/matrix_test.sh tests/batch/relight_test.sh tests/data/batch/env.pbrt \
	tests/data/batch/env_turned.pbrt tests/data/batch/gray.pfm tests/data/batch/wide.pfm
# --- alpha, ID AOVs and Cryptomatte (issue 28) ---
check_PROGRAMS += tests/batch/matte_probe
tests_batch_matte_probe_LDADD = $(CV_LIBS)
TESTS += tests/batch/mattes_test.sh
EXTRA_DIST += tests/batch/mattes_test.sh tests/data/batch/mattes.pbrt tests/data/batch/mattes.yaml
# --- rlpath renders: never black, never NaN; non-finite values reported ---
TESTS += tests/batch/rlpath_finite_test.sh tests/batch/rlpath_frozen_test.sh \
    tests/batch/rlpath_unguided_test.sh tests/batch/sdtree_share_test.sh
EXTRA_DIST += tests/batch/rlpath_finite_test.sh tests/batch/rlpath_frozen_test.sh \
    tests/batch/rlpath_unguided_test.sh tests/batch/sdtree_share_test.sh \
    tests/data/batch/cornell_box.pbrt
# --- bdpt's mattes are path's (issue 27) ---
TESTS += tests/batch/mattes_bdpt_test.sh
EXTRA_DIST += tests/batch/mattes_bdpt_test.sh
# --- --scene-root when rendering, --check and --dry-run ---
TESTS += tests/batch/scene_root_test.sh
EXTRA_DIST += tests/batch/scene_root_test.sh
# --- exit status 70: out of host memory ---
TESTS += tests/batch/out_of_memory_test.sh
EXTRA_DIST += tests/batch/out_of_memory_test.sh
# --- color.exposure and color.look reach the PNG ---
TESTS += tests/batch/color_test.sh
EXTRA_DIST += tests/batch/color_test.sh
