/* shard_test.c: for 20 jobs and every shard count from 1 to 7, each job is
 * in exactly one shard and shard sizes differ by at most one; invalid shard
 * arguments select nothing; Slurm array tasks with an offset and a step map
 * to shards 0..count-1. */
#include <stdbool.h>

#include "manifest/shard.h"
#include "tests/tap.h"

int main(void)
{
    const size_t n_jobs = 20;
    for (unsigned count = 1; count <= 7; count++) {
        unsigned times[20] = {0};
        size_t size_min = n_jobs, size_max = 0;
        for (unsigned index = 0; index < count; index++) {
            size_t size = 0;
            for (size_t j = 0; j < n_jobs; j++) {
                if (cv_shard_select(n_jobs, index, count, j)) {
                    times[j]++;
                    size++;
                }
            }
            if (size < size_min)
                size_min = size;
            if (size > size_max)
                size_max = size;
        }
        bool exact = true;
        for (size_t j = 0; j < n_jobs; j++)
            exact &= times[j] == 1;
        tap_ok(exact, "N=%u: every job in exactly one shard", count);
        tap_ok(size_max - size_min <= 1, "N=%u: shard sizes %zu..%zu", count, size_min, size_max);
    }
    tap_ok(cv_shard_select(20, 2, 3, 5), "job 5 of 20 is in shard 2 of 3 (round-robin)");
    tap_ok(!cv_shard_select(20, 0, 0, 0), "count 0 selects nothing");
    tap_ok(!cv_shard_select(20, 3, 3, 3), "index >= count selects nothing");
    tap_ok(!cv_shard_select(20, 0, 1, 20), "job index past the end selects nothing");
    tap_ok(cv_shard_valid(0, 1) && !cv_shard_valid(1, 1) && !cv_shard_valid(0, 0),
           "cv_shard_valid");

    /* Slurm "--array=1-9:2": tasks 1, 3, 5, 7, 9 are shards 0..4 of 5. */
    unsigned index, n;
    const char *why = NULL;
    bool all = true;
    for (unsigned id = 1, want = 0; id <= 9; id += 2, want++) {
        bool got = cv_shard_from_array(id, 1, 9, 2, 5, &index, &n, &why);
        all &= got && index == want && n == 5;
    }
    tap_ok(all, "--array=1-9:2: tasks 1,3,5,7,9 are shards 0..4 of 5");
    bool refused = !cv_shard_from_array(4, 1, 9, 2, 5, &index, &n, &why);
    tap_ok(refused, "task 4 of 1-9:2 is refused (%s)", refused ? why : "");
    tap_ok(!cv_shard_from_array(11, 1, 9, 2, 5, &index, &n, &why), "task 11 of 1-9:2 is refused");
    tap_ok(cv_shard_from_array(12, 10, 12, 0, 0, &index, &n, &why) && index == 2 && n == 3,
           "--array=10-12 (no step, no count): task 12 is shard 2 of 3");
    tap_ok(!cv_shard_from_array(4, 1, 6, 1, 3, &index, &n, &why),
           "--array=1,4,6 (count 3, range 1-6): refused, cannot be mapped");
    return tap_done();
}
