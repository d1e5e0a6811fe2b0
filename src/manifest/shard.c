/* shard.c: see shard.h. */
#include "manifest/shard.h"

bool cv_shard_valid(unsigned index, unsigned count)
{
    return count >= 1 && index < count;
}

bool cv_shard_select(size_t n_jobs, unsigned index, unsigned count, size_t job_i)
{
    if (!cv_shard_valid(index, count) || job_i >= n_jobs)
        return false;
    return job_i % count == index;
}
