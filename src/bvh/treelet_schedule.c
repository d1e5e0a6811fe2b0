/* treelet_schedule.c: see treelet_schedule.h. */
#include "bvh/treelet_schedule.h"

static int popcount(uint32_t x)
{
    int c = 0;
    for (; x; x &= x - 1)
        c++;
    return c;
}

/* The bits of m placed, in order, on the set bits of mask. */
static uint32_t deposit(uint32_t m, uint32_t mask)
{
    uint32_t r = 0;
    for (; mask; mask &= mask - 1, m >>= 1)
        if (m & 1)
            r |= mask & (~mask + 1);
    return r;
}

size_t cv_treelet_schedule(int leaves, uint32_t *out)
{
    if (leaves < 3 || leaves > 8)
        return 0;
    uint32_t full = (1u << leaves) - 1;
    size_t n = 0, start[10];   /* start[k]: the first subset of k leaves */
    for (int k = 2; k <= leaves; k++) {
        start[k] = n;
        for (uint32_t s = 1; s <= full; s++)
            if (popcount(s) == k)
                out[n++] = s;
    }
    start[leaves + 1] = n;
    for (int k = 3; k <= leaves; k++)
        for (uint32_t m = 0; m + 1 < (1u << (k - 1)); m++)
            for (size_t j = start[k]; j < start[k + 1]; j++) {
                uint32_t s = out[j], low = s & (~s + 1);
                out[n++] = s | (low | deposit(m, s ^ low)) << 8;
            }
    return n;
}
