# tests/manifest: the manifest reader, settings hash, shards and man page.
check_PROGRAMS += tests/manifest/keys_test tests/manifest/manifest_test tests/manifest/manifest_edge_test \
	tests/manifest/hash_test tests/manifest/shard_test tests/manifest/key_set_test tests/manifest/yaml_caps_test \
	tests/manifest/fuzz_manifest
TESTS += tests/manifest/keys_test tests/manifest/manifest_test tests/manifest/manifest_edge_test \
	tests/manifest/hash_test tests/manifest/shard_test tests/manifest/key_set_test tests/manifest/yaml_caps_test \
	tests/manifest/man_lint_test.sh tests/manifest/fuzz_manifest_test.sh
tests_manifest_keys_test_LDADD = $(CV_LIBS)
tests_manifest_manifest_test_LDADD = $(CV_LIBS)
tests_manifest_manifest_edge_test_LDADD = $(CV_LIBS)
tests_manifest_hash_test_LDADD = $(CV_LIBS)
tests_manifest_shard_test_LDADD = $(CV_LIBS)
tests_manifest_key_set_test_LDADD = $(CV_LIBS)
tests_manifest_yaml_caps_test_LDADD = $(CV_LIBS)
tests_manifest_fuzz_manifest_LDADD = $(CV_LIBS)
EXTRA_DIST += tests/manifest/man_lint_test.sh tests/manifest/fuzz_manifest_test.sh \
	tests/data/manifest/good.yaml \
	tests/data/manifest/err_unknown_key.yaml \
	tests/data/manifest/err_wrong_type.yaml \
	tests/data/manifest/err_negative_spp.yaml \
	tests/data/manifest/err_missing_scene.yaml \
	tests/data/manifest/err_duplicate_names.yaml \
	tests/data/manifest/err_syntax.yaml \
	tests/data/manifest/err_missing_version.yaml \
	tests/data/manifest/err_many.yaml \
	tests/data/manifest/scenes/tiny.pbrt \
	tests/data/manifest/scenes/other.pbrt
# --- a job's matrix (issue 28) ---
check_PROGRAMS += tests/manifest/matrix_test
TESTS += tests/manifest/matrix_test
tests_manifest_matrix_test_LDADD = $(CV_LIBS)
