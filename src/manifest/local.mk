# src/manifest: the batch manifest reader (libyaml) and job sharding.
libcavalry_a_SOURCES += \
	src/manifest/diag.c src/manifest/diag.h \
	src/manifest/key_set.c src/manifest/key_set.h \
	src/manifest/yaml_scan.c src/manifest/yaml_scan.h \
	src/manifest/yaml_view.c src/manifest/yaml_view.h \
	src/manifest/enums.c src/manifest/enums.h \
	src/manifest/keys.c src/manifest/keys.h \
	src/manifest/job_parse.c src/manifest/job_parse.h \
	src/manifest/job_hash.c src/manifest/job_hash.h \
	src/manifest/matrix.c src/manifest/matrix.h \
	src/manifest/manifest.c src/manifest/manifest.h \
	src/manifest/shard.c src/manifest/shard.h
