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

bool cv_shard_from_array(unsigned id, unsigned min, unsigned max, unsigned step, unsigned count,
                         unsigned *index, unsigned *n, const char **why)
{
    if (step == 0)
        step = 1;
    if (max < min || id < min || id > max) {
        *why = "the task id is outside the array's range";
        return false;
    }
    if ((id - min) % step != 0) {
        *why = "the task id is not the array's minimum plus a multiple of its step";
        return false;
    }
    unsigned tasks = (max - min) / step + 1;
    if (count && count != tasks) {
        *why = "the array's task count does not match its range and step (an id list?)";
        return false;
    }
    *index = (id - min) / step;
    *n = tasks;
    return true;
}
