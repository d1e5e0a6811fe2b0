/* sah_ref.h: the CPU binned-SAH split that the BVH tests' reference
 * (bvh_test_util.h: ref_sah) and bench/bvh_work's reference tree share:
 * surface area, and the best split of a node's triangles over equal bins
 * of their centroids on each axis (Wald 2007), by the same cost as the
 * GPU build's (left area x count + right area x count). Tools only: the
 * renderer's tree is built on the GPU (src/bvh/). */
#ifndef CV_TESTS_BVH_SAH_REF_H
#define CV_TESTS_BVH_SAH_REF_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

/* Half the surface area of a box (0 for an empty one). */
static inline double half_area3(const float lo[3], const float hi[3])
{
    double e[3];
    for (int k = 0; k < 3; k++)
        e[k] = hi[k] > lo[k] ? (double)hi[k] - lo[k] : 0.0;
    return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}

/* Triangle boxes lo/hi and centroids c, indexed by triangle. */
struct sah_ref_tris {
    const float (*lo)[3], (*hi)[3], (*c)[3];
};

/* The box lo..hi of triangles ids[begin, end) and the box clo..chi of
 * their centroids. */
static inline void sah_ref_bounds(const struct sah_ref_tris *t, const uint32_t *ids, uint32_t begin,
                                  uint32_t end, float lo[3], float hi[3], float clo[3], float chi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = clo[k] = INFINITY;
        hi[k] = chi[k] = -INFINITY;
    }
    for (uint32_t i = begin; i < end; i++) {
        uint32_t id = ids[i];
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], t->lo[id][k]);
            hi[k] = fmaxf(hi[k], t->hi[id][k]);
            clo[k] = fminf(clo[k], t->c[id][k]);
            chi[k] = fmaxf(chi[k], t->c[id][k]);
        }
    }
}

static inline int sah_ref_bin(float c, float clo, double ext, int bins)
{
    int q = (int)((c - clo) / ext * bins);
    return q < 0 ? 0 : q >= bins ? bins - 1 : q;
}

/* Splits ids[begin, end) (centroid box clo..chi) at the cheapest of the
 * bins - 1 planes per axis and returns where the right part starts; all
 * centroids equal: at the middle by index. */
static inline uint32_t sah_ref_split(const struct sah_ref_tris *t, uint32_t *ids, uint32_t begin,
                                     uint32_t end, const float clo[3], const float chi[3], int bins)
{
    double best = INFINITY;
    int best_axis = -1, best_bin = 0;
    float (*blo)[3] = malloc(sizeof(*blo) * (size_t)bins * 2), (*bhi)[3] = blo + bins;
    uint32_t *cnt = malloc(sizeof(*cnt) * (size_t)bins * 2), *rcnt = cnt + bins;
    double *rarea = malloc(sizeof(*rarea) * (size_t)bins);
    for (int axis = 0; axis < 3; axis++) {
        double ext = (double)chi[axis] - clo[axis];
        if (!(ext > 0))
            continue;
        for (int q = 0; q < bins; q++) {
            cnt[q] = 0;
            for (int k = 0; k < 3; k++) {
                blo[q][k] = INFINITY;
                bhi[q][k] = -INFINITY;
            }
        }
        for (uint32_t i = begin; i < end; i++) {
            uint32_t id = ids[i];
            int q = sah_ref_bin(t->c[id][axis], clo[axis], ext, bins);
            cnt[q]++;
            for (int k = 0; k < 3; k++) {
                blo[q][k] = fminf(blo[q][k], t->lo[id][k]);
                bhi[q][k] = fmaxf(bhi[q][k], t->hi[id][k]);
            }
        }
        float slo[3] = {INFINITY, INFINITY, INFINITY}, shi[3] = {-INFINITY, -INFINITY, -INFINITY};
        uint32_t sc = 0;
        for (int q = bins - 1; q > 0; q--) {
            for (int k = 0; k < 3; k++) {
                slo[k] = fminf(slo[k], blo[q][k]);
                shi[k] = fmaxf(shi[k], bhi[q][k]);
            }
            sc += cnt[q];
            rarea[q] = half_area3(slo, shi);
            rcnt[q] = sc;
        }
        for (int k = 0; k < 3; k++) {
            slo[k] = INFINITY;
            shi[k] = -INFINITY;
        }
        sc = 0;
        for (int q = 0; q < bins - 1; q++) {
            for (int k = 0; k < 3; k++) {
                slo[k] = fminf(slo[k], blo[q][k]);
                shi[k] = fmaxf(shi[k], bhi[q][k]);
            }
            sc += cnt[q];
            if (sc == 0 || rcnt[q + 1] == 0)
                continue;
            double c = half_area3(slo, shi) * sc + rarea[q + 1] * rcnt[q + 1];
            if (c < best) {
                best = c;
                best_axis = axis;
                best_bin = q;
            }
        }
    }
    free(blo);
    free(cnt);
    free(rarea);
    if (best_axis < 0)
        return begin + (end - begin) / 2;
    double ext = (double)chi[best_axis] - clo[best_axis];
    uint32_t i = begin, j = end;
    while (i < j) {
        uint32_t id = ids[i];
        if (sah_ref_bin(t->c[id][best_axis], clo[best_axis], ext, bins) <= best_bin) {
            i++;
        } else {
            ids[i] = ids[--j];
            ids[j] = id;
        }
    }
    return i;
}

#endif
