/* median_split.c: see median_split.h. */
#include <math.h>
#include <stdlib.h>

#include "base/mem.h"
#include "bvh/median_split.h"

struct keyed {
    float key;
    uint32_t index;
};

static int cmp_keyed(const void *a, const void *b)
{
    const struct keyed *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key ? 1 : (x->index > y->index) - (x->index < y->index);
}

void cv_median_split(uint32_t *order, uint32_t count, const float (*lo)[3], const float (*hi)[3])
{
    float clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t k = 0; k < count; k++)
        for (int a = 0; a < 3; a++) {
            float c = 0.5f * (lo[order[k]][a] + hi[order[k]][a]);
            clo[a] = fminf(clo[a], c);
            chi[a] = fmaxf(chi[a], c);
        }
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (chi[a] - clo[a] > chi[axis] - clo[axis])
            axis = a;
    struct keyed *k = cv_xcalloc(count, sizeof(*k));
    for (uint32_t i = 0; i < count; i++)
        k[i] = (struct keyed){lo[order[i]][axis] + hi[order[i]][axis], order[i]};
    qsort(k, count, sizeof(*k), cmp_keyed);
    for (uint32_t i = 0; i < count; i++)
        order[i] = k[i].index;
    free(k);
}
