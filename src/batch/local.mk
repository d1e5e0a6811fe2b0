# src/batch: runs a manifest's jobs.
libcavalry_a_SOURCES += \
	src/batch/batch.c src/batch/batch.h \
	src/batch/job_lock.c src/batch/job_lock.h \
	src/batch/matte_layers.c src/batch/matte_layers.h \
	src/batch/pass_size.c src/batch/pass_size.h \
	src/batch/plan.c src/batch/plan.h \
	src/batch/progress.c src/batch/progress.h \
	src/batch/progress_wire.c src/batch/progress_wire.h \
	src/batch/run_job.c src/batch/run_job.h \
	src/batch/signals.c src/batch/signals.h \
	src/batch/workers.c src/batch/workers.h
