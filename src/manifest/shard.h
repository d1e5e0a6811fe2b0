/* shard.h: splitting a manifest's jobs over several farm tasks
 * (--shard-index/--shard-count, SLURM array tasks, Kubernetes indexed jobs).
 * Round-robin by job index: job i belongs to shard i mod count. It needs no
 * coordination, depends only on the manifest's job order, puts every job in
 * exactly one shard and keeps shards within one job of each other in size. */
#ifndef CV_MANIFEST_SHARD_H
#define CV_MANIFEST_SHARD_H

#include <stdbool.h>
#include <stddef.h>

/* Whether job_i (0-based, < n_jobs) runs in shard index (0-based) of count.
 * False for any invalid argument (count 0, index >= count, job_i >= n_jobs);
 * callers check index and count with cv_shard_valid first to report them. */
bool cv_shard_select(size_t n_jobs, unsigned index, unsigned count, size_t job_i);

/* count >= 1 and index < count. */
bool cv_shard_valid(unsigned index, unsigned count);

#endif
