/* shard.h: splitting a manifest's jobs over several farm tasks
 * (--shard-index/--shard-count, Slurm array tasks, Kubernetes indexed jobs).
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

/* A Slurm job array's task as a shard: "--array=1-9:2" runs tasks 1, 3, 5, 7
 * and 9 (SLURM_ARRAY_TASK_MIN 1, MAX 9, STEP 2, COUNT 5), which become shards
 * 0 to 4 of 5. step 0 means not given (1); count 0 means not given (derived
 * from min, max and step). False, with *why set to a sentence, for a task
 * that is not min + k * step within [min, max], or for an array whose task
 * count does not match its range and step (a list such as "--array=1,4,6"),
 * which cannot be mapped to shards without knowing every task id. */
bool cv_shard_from_array(unsigned id, unsigned min, unsigned max, unsigned step, unsigned count,
                         unsigned *index, unsigned *n, const char **why);

#endif
