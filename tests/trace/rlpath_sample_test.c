/* rlpath_sample_test.c: the learned directional distribution of the rlpath
 * tables (glsl/trace/rlpath/guide.glsl, its guide texels built by
 * rebuild.comp) on the GPU against a host reference: the table layout from
 * the options; a key filled with a known random pattern (some bins 0, so
 * the floor matters, and some with emitted light, which guiding follows by
 * default and leaves to light sampling with rlpath.guide: indirect, both
 * tested), at 128 bins (two coarse CDF texels) and at 990 (a
 * binary search over sixteen): directions drawn from it
 * follow its pdf (chi-square over a histogram twice as fine as the bins in
 * each coordinate, so uniformity within a bin is tested too; p >= 0.01), the
 * pdf reported at sampling equals the one evaluated and the host's, and the
 * pdf integrates to 1 over the sphere; the same for the one-sample mixture
 * with a Lambertian lobe, whose density must be m pQ + (1 - m) pBSDF; the
 * key's guiding weight m, reduced while it has few visits; the key's
 * irradiance (Q, emitted light included, times the cosine about the
 * class axis, summed over the bins) against the host's. */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/trace/rlpath_stats.h"
#include "trace/rlpath.h"

#define PI 3.14159265358979323846

static const double normal[3] = {0.3, -0.5, 0.812404};

/* Host reference of the bin map and the learned pdf (guide.glsl). */
static uint32_t ref_bin(const CvRlParams *p, const double w[3])
{
    uint32_t nz = p->dirs.x, np = p->dirs.y;
    double fz = (w[2] + 1) * 0.5 * nz, u = (atan2(w[1], w[0]) + PI) / (2 * PI);
    uint32_t iz = fz <= 0 ? 0 : (uint32_t)fz, ip = u <= 0 ? 0 : (uint32_t)(u * np);
    if (iz >= nz) iz = nz - 1;
    if (ip >= np) ip = np - 1;
    return iz * np + ip;
}

static double ref_weight(const float *q, uint32_t bin, double e)
{
    return q[bin] + e;
}

static double ref_prob(const CvRlParams *p, const float *q, uint32_t bin)
{
    double s = 0, n = p->dirs.z;
    for (uint32_t b = 0; b < p->dirs.z; b++)
        s += q[b];
    double e = fmax(p->grid_scale.w * s / n, 1e-20), total = 0;
    for (uint32_t b = 0; b < p->dirs.z; b++)
        total += ref_weight(q, b, e);
    return ref_weight(q, bin, e) / total;
}

static double ref_pdf(const CvRlParams *p, const float *q, const double w[3])
{
    return ref_prob(p, q, ref_bin(p, w)) * p->dirs.z / (4 * PI);
}

/* The key's irradiance as rebuild.comp sums it: Q (both parts) times
 * max(cos, 0) to `axis` at 2 x 2 points per bin, times the bin's solid
 * angle. */
static double ref_irradiance(const CvRlParams *p, const float *q, const float *emitted,
                             const double axis[3])
{
    uint32_t nz = p->dirs.x, np = p->dirs.y;
    double irr = 0;
    for (uint32_t b = 0; b < p->dirs.z; b++) {
        double c = 0;
        for (int i = 0; i < 4; i++) {
            double z = -1 + 2 * (b / np + 0.25 + 0.5 * (i & 1)) / nz;
            double phi = -PI + 2 * PI * (b % np + 0.25 + 0.5 * (i >> 1)) / np;
            double r = sqrt(fmax(0, 1 - z * z));
            c += fmax(0, r * cos(phi) * axis[0] + r * sin(phi) * axis[1] + z * axis[2]);
        }
        irr += (q[b] + (emitted ? emitted[b] : 0)) * c * PI / p->dirs.z;
    }
    return irr;
}

static double lambert(const double w[3])
{
    double c = w[0] * normal[0] + w[1] * normal[1] + w[2] * normal[2];
    return c > 0 ? c / PI : 0;
}

/* Histogram cell of w on an equal-area grid of hz x hp cells. */
static size_t hist_cell(const double w[3], uint32_t hz, uint32_t hp)
{
    double fz = (w[2] + 1) * 0.5 * hz, u = (atan2(w[1], w[0]) + PI) / (2 * PI);
    uint32_t iz = fz <= 0 ? 0 : (uint32_t)fz, ip = u <= 0 ? 0 : (uint32_t)(u * hp);
    if (iz >= hz) iz = hz - 1;
    if (ip >= hp) ip = hp - 1;
    return (size_t)iz * hp + ip;
}

static void grid_dir(uint32_t iz, uint32_t ip, double fz, double fp, uint32_t hz, uint32_t hp,
                     double w[3])
{
    double z = -1 + 2 * (iz + fz) / hz, phi = -PI + 2 * PI * (ip + fp) / hp;
    double r = sqrt(fmax(0, 1 - z * z));
    w[0] = r * cos(phi);
    w[1] = r * sin(phi);
    w[2] = z;
}

struct rig {
    struct cv_gpu *gpu;
    CvRlParams params;
    GLuint ubo, table, guide, out, in, table_tex, guide_tex;
    uint32_t key;   /* cell 0, the class of `normal` */
    bool indirect;  /* rebuild with CV_RL_GUIDE_INDIRECT */
};

static bool run(struct rig *g, int mode, uint32_t n, uint32_t seed, float *out,
                struct cv_error *err);
static void set_table(struct rig *g, const float *q, const float *emitted, uint32_t visits,
                      struct cv_error *err);

/* Whether the whole guide table and the test key's learning sums are finite
 * after a rebuild; *bin_reset: whether bin `bin` of the key sums to 0. */
static bool tables_finite(struct rig *g, uint32_t bin, bool *bin_reset, struct cv_error *err)
{
    size_t gb = (size_t)cv_rlpath_guide_bytes(&g->params);
    size_t tb = (size_t)cv_rlpath_table_bytes(&g->params);
    float *guide = malloc(gb), *table = malloc(tb);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    bool ok = cv_buffer_read(g->guide, 0, gb, guide, err) &&
              cv_buffer_read(g->table, 0, tb, table, err);
    for (size_t i = 0; ok && i < gb / 4; i++)
        ok = isfinite(guide[i]);
    const float *k = table + (size_t)g->key * CV_RL_LEARN_TEXELS(g->params.dirs.z);
    for (uint32_t b = 0; ok && b < g->params.dirs.z; b++)
        ok = isfinite(k[3 * b]) && isfinite(k[3 * b + 2]);
    *bin_reset = k[3 * bin] == 0;
    free(guide);
    free(table);
    return ok;
}

/* Bad sums in the learning table (one that overflowed to infinity; finite
 * means whose sum over the bins overflows) give a finite guide: sampling
 * draws finite, positive pdfs from it. A float sum of targets can overflow
 * where a path's throughput over a tiny pdf makes a huge target. */
static void test_poisoned(struct rig *g, float *q, uint32_t nb, float *out, struct cv_error *err)
{
    for (int c = 0; c < 2; c++) {
        for (uint32_t b = 0; b < nb; b++)
            q[b] = c == 0 ? 1.0f : 1e37f;
        if (c == 0)
            q[5] = INFINITY;
        const char *what = c == 0 ? "a bin summed to infinity" : "bins whose total overflows";
        set_table(g, q, NULL, c == 0 ? 100 : 1, err);
        bool reset = false;
        tap_ok(tables_finite(g, 5, &reset, err), "%s: guide and sums finite after the rebuild",
               what);
        if (c == 0)
            tap_ok(reset, "%s: the bin starts again at 0", what);
        if (tap_ok(run(g, 0, 1024, 3, out, err), "%s: sample: %s", what, err->msg)) {
            uint32_t bad = 0, skewed = 0;
            for (uint32_t i = 0; i < 1024; i++) {
                const float *o = out + 8 * (size_t)i;
                /* equal bins: uniform, however large */
                if (c == 1 && !(fabs(o[4] * 4 * PI - 1) < 1e-4))
                    skewed++;
                if (!(o[3] > 0) || !(o[4] > 0) || !isfinite(o[3]) || !isfinite(o[4]) ||
                    !isfinite(o[6]) || !isfinite(o[7]) || !isfinite(o[0] + o[1] + o[2]))
                    bad++;
            }
            tap_ok(bad == 0, "%s: every pdf and the weight finite and positive (%u not)", what,
                   bad);
            if (c == 1)
                tap_ok(skewed == 0, "%s: equal bins sample uniformly (%u pdfs not 1 / 4 pi)",
                       what, skewed);
        }
    }
    memset(q, 0, nb * sizeof(float));
}

/* Runs TEST_MODE mode over n items; out gets 8 floats per item. */
static bool run(struct rig *g, int mode, uint32_t n, uint32_t seed, float *out,
                struct cv_error *err)
{
    char def[32];
    snprintf(def, sizeof(def), "TEST_MODE=%d", mode);
    const char *defines[] = {def, NULL};
    struct cv_program *prog = cv_program_get(g->gpu, "trace/rlpath/test_sample.comp", defines, err);
    if (!prog)
        return false;
    glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_RLPATH, g->ubo);
    glBindImageTexture(CV_IMAGE_RL_Q, g->table_tex, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glBindTextureUnit(CV_TEXUNIT_RL_GUIDE, g->guide_tex);
    cv_buffer_bind(g->out, CV_BIND_RL_PROBE_OUT);
    cv_buffer_bind(g->in, CV_BIND_RL_PROBE_IN);
    glUseProgram(prog->id);
    glUniform1ui(0, n);
    glUniform1ui(1, seed);
    cv_program_dispatch_1d(prog, n);
    return cv_buffer_read(g->out, 0, (size_t)n * 8 * sizeof(float), out, err) &&
           cv_gl_check(err, "test_sample mode %d", mode);
}

/* Fills the test key with `visits` per bin whose targets' means are q
 * without and `emitted` (NULL: none) in their emitted part, marks it
 * changed and builds its distribution with rebuild.comp, as the renderer
 * does. */
static void set_table(struct rig *g, const float *q, const float *emitted, uint32_t visits,
                      struct cv_error *err)
{
    uint32_t n = g->params.dirs.z, stride = CV_RL_LEARN_TEXELS(n);
    size_t bytes = (size_t)cv_rlpath_table_bytes(&g->params);
    uint32_t *raw = calloc(bytes / 4, sizeof(uint32_t));
    uint32_t *k = raw + (size_t)g->key * stride;
    for (uint32_t b = 0; b < n; b++) {
        /* the sums over the visits are the means */
        float sum = q[b] * (float)visits, sum_e = emitted ? emitted[b] * (float)visits : 0;
        memcpy(&k[3 * b], &sum, sizeof(float));
        k[3 * b + 1] = visits;
        memcpy(&k[3 * b + 2], &sum_e, sizeof(float));
    }
    k[3 * n] = 1;   /* the dirty flag */
    tap_ok(cv_buffer_upload(g->table, 0, bytes, raw, err), "table upload");
    free(raw);
    const char *defines[] = {g->indirect ? "CV_RL_GUIDE_INDIRECT" : NULL, NULL};
    struct cv_program *rebuild = cv_program_get(g->gpu, "trace/rlpath/rebuild.comp", defines, err);
    if (!tap_ok(rebuild != NULL, "rebuild program: %s", err->msg))
        return;
    glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_RLPATH, g->ubo);
    glBindImageTexture(CV_IMAGE_RL_Q, g->table_tex, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(CV_IMAGE_RL_GUIDE, g->guide_tex, 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_RGBA32F);
    cv_rlpath_dispatch_rebuild(rebuild, &g->params);
}

static void test_layout(void)
{
    struct cv_error err = {{0}};
    CvRlParams p;
    const float lo[3] = {0, 0, 0}, hi[3] = {2, 1, 0.5f};
    tap_ok(cv_rlpath_layout(lo, hi, 0, 0, -1, &p, &err), "layout with defaults: %s", err.msg);
    const uint32_t g = CV_RL_DEFAULT_GRID;
    tap_ok(p.dims.x == g && p.dims.y == g / 2 && p.dims.z == g / 4 && p.dims.w == g * g * g / 8,
           "default grid %u along the longest axis, proportional elsewhere (%u %u %u)", g,
           p.dims.x, p.dims.y, p.dims.z);
    tap_ok(p.dirs.x == 8 && p.dirs.y == 16 && p.dirs.z == 128, "128 directions: 8 x 16 (%u x %u)",
           p.dirs.x, p.dirs.y);
    tap_ok(p.dirs.w == p.dims.w * CV_RL_ORIENTS, "%u keys: 6 normal classes per cell", p.dirs.w);
    tap_ok(p.grid_min.w == CV_RL_DEFAULT_MIX, "default mix %g", p.grid_min.w);
    tap_ok(p.grid_min.x < 0 && p.grid_min.x + p.dims.x / p.grid_scale.x > 2,
           "grid covers the bounds with padding");
    bool ok = cv_rlpath_layout(lo, hi, 4, 32, 0.25f, &p, &err);
    tap_ok(ok && p.dirs.z == 32 && p.dims.x == 4 && p.grid_min.w == 0.25f,
           "explicit options (%u x %u bins)", p.dirs.x, p.dirs.y);
    ok = cv_rlpath_layout(lo, hi, 4, 32, 0, &p, &err);
    tap_ok(ok && p.grid_min.w == 0, "mix 0 stays 0 (BSDF sampling alone): %g", p.grid_min.w);
    tap_ok(!cv_rlpath_layout(lo, hi, 4, 32, 1.5f, &p, &err) && strstr(err.msg, "mix"),
           "mix above 1 is an error: %s", err.msg);
    tap_ok(!cv_rlpath_layout(lo, hi, 4, 5000, 0.5f, &p, &err) && strstr(err.msg, "directions"),
           "too many directions is an error: %s", err.msg);
    const float inf[3] = {INFINITY, INFINITY, INFINITY}, ninf[3] = {-INFINITY, -INFINITY, -INFINITY};
    tap_ok(cv_rlpath_layout(inf, ninf, 8, 8, 0.5f, &p, &err) && p.dims.w == 1,
           "empty bounds give one cell");
}

/* Everything on the GPU for a key of about `directions` bins. */
static void test_bins(struct cv_gpu *gpu, uint32_t directions, bool indirect)
{
    struct rig g = {0};
    g.gpu = gpu;
    g.indirect = indirect;
    struct cv_error err = {{0}};
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const float m = 0.5f;
    bool laid = cv_rlpath_layout(lo, hi, 1, directions, m, &g.params, &err);
    if (!tap_ok(laid, "layout of %u directions: %u x %u bins, guide %s: %s", directions,
                g.params.dirs.x, g.params.dirs.y, indirect ? "indirect" : "all", err.msg))
        return;
    const uint32_t nb = g.params.dirs.z, N = 1u << 18;
    g.key = 4;   /* cell 0, +z */
    const uint32_t HZ = 2 * g.params.dirs.x, HP = 2 * g.params.dirs.y;
    /* the quadrature grid (QZ x QP, at least 256 x 512) splits every bin
     * alike, so the midpoint rule integrates the learned pdf exactly */
    const uint32_t QZ = g.params.dirs.x * ((255 + g.params.dirs.x) / g.params.dirs.x),
                   QP = g.params.dirs.y * ((511 + g.params.dirs.y) / g.params.dirs.y);
    g.ubo = cv_buffer_create(sizeof(g.params), &g.params, "test rl params", &err);
    g.table = cv_buffer_create(cv_rlpath_table_bytes(&g.params), NULL, "test rl table", &err);
    g.guide = cv_buffer_create(cv_rlpath_guide_bytes(&g.params), NULL, "test rl guide", &err);
    g.out = cv_buffer_create((size_t)(N > QZ * QP ? N : QZ * QP) * 8 * sizeof(float), NULL,
                             "test out", &err);
    float *inq = calloc((size_t)QZ * QP * 4, sizeof(float));
    for (uint32_t iz = 0; iz < QZ; iz++)
        for (uint32_t ip = 0; ip < QP; ip++) {
            double w[3];
            grid_dir(iz, ip, 0.5, 0.5, QZ, QP, w);
            float *v = inq + 4 * ((size_t)iz * QP + ip);
            v[0] = (float)w[0], v[1] = (float)w[1], v[2] = (float)w[2];
        }
    g.in = cv_buffer_create((size_t)QZ * QP * 4 * sizeof(float), inq, "test in", &err);
    if (g.table)
        g.table_tex = cv_buffer_texture(g.table, GL_R32UI,
                                        cv_rlpath_table_bytes(&g.params) / 4, &err);
    if (g.guide)
        g.guide_tex = cv_buffer_texture(g.guide, GL_RGBA32F,
                                        cv_rlpath_guide_bytes(&g.params) / 16, &err);
    if (!tap_ok(g.ubo && g.table && g.guide && g.out && g.in && g.table_tex && g.guide_tex,
                "buffers: %s", err.msg))
        return;
    float *out = malloc((size_t)(N > QZ * QP ? N : QZ * QP) * 8 * sizeof(float));

    /* an empty key is uniform */
    float *q = calloc(nb, sizeof(float));
    const uint32_t trusted = 100;   /* visits per bin: the full weight */
    set_table(&g, q, NULL, trusted, &err);
    if (tap_ok(run(&g, 0, 1024, 1, out, &err), "sample empty cell: %s", err.msg)) {
        double worst = 0;
        for (uint32_t i = 0; i < 1024; i++) {
            double w[3] = {out[8 * i], out[8 * i + 1], out[8 * i + 2]};
            double r = ref_pdf(&g.params, q, w);
            worst = fmax(worst, fabs(out[8 * i + 4] - r) / r);
        }
        tap_ok(worst < 1e-4, "empty key: pdf is uniform (worst relative error %g)",
               worst);
        tap_ok(out[6] == m, "a key with %u visits per bin guides with the full weight (%g)",
               trusted, out[6]);
    }

    /* a young key guides less: m times its mean visits per bin over the trust */
    set_table(&g, q, NULL, 1, &err);
    if (tap_ok(run(&g, 0, 64, 1, out, &err), "sample a young key: %s", err.msg)) {
        double want = m * (1.0 / CV_RL_TRUST_VISITS);
        tap_ok(fabs(out[6] - want) < 1e-6, "a key with 1 visit per bin guides with weight %g "
               "(%g)", want, out[6]);
    }

    /* keys whose sums went bad build a finite distribution (a CDF of
     * inf / inf would be NaN: every pdf and MIS weight of the key's hits
     * NaN, their light dropped); then every sample is finite */
    test_poisoned(&g, q, nb, out, &err);

    /* a known pattern: a peaked random fill, a quarter of the bins zero */
    uint32_t state = 2024;
    for (uint32_t b = 0; b < nb; b++) {
        state = state * 1664525u + 1013904223u;
        double u = (state >> 8) / 16777216.0;
        q[b] = (b % 4 == 1) ? 0.0f : (float)(u * u * u * 10);
    }
    q[37] = 40;   /* one bright bin */
    /* lamps seen directly in some bins: bright; guided by (qg) unless the
     * guide is indirect */
    float *emitted = calloc(nb, sizeof(float)), *qg = calloc(nb, sizeof(float));
    for (uint32_t b = 3; b < nb; b += 11)
        emitted[b] = 500;
    for (uint32_t b = 0; b < nb; b++)
        qg[b] = q[b] + (indirect ? 0 : emitted[b]);

    /* a bin past CV_RL_MAX_VISITS: the rebuild halves visits, keeps Q */
    const uint32_t many = 3 * CV_RL_MAX_VISITS;
    set_table(&g, q, emitted, many, &err);
    {
        uint32_t stride = CV_RL_LEARN_TEXELS(nb);
        uint32_t *raw = malloc((size_t)stride * 4);
        bool ok = cv_buffer_read(g.table, (size_t)g.key * stride * 4, (size_t)stride * 4, raw, &err);
        uint32_t bad_n = 0, bad_q = 0;
        for (uint32_t b = 0; ok && b < nb; b++) {
            float sum, sum_e;
            memcpy(&sum, &raw[3 * b], sizeof(float));
            memcpy(&sum_e, &raw[3 * b + 2], sizeof(float));
            if (raw[3 * b + 1] != many / 2)
                bad_n++;
            if (fabs(sum / raw[3 * b + 1] - q[b]) > 1e-5 * q[b] + 1e-30 ||
                fabs(sum_e / raw[3 * b + 1] - emitted[b]) > 1e-5 * emitted[b] + 1e-30)
                bad_q++;
        }
        tap_ok(ok && bad_n == 0 && bad_q == 0, "%u visits halved to %u with Q kept "
               "(%u visit counts, %u Q differ): %s", many, many / 2, bad_n, bad_q, err.msg);
        free(raw);
    }
    set_table(&g, q, emitted, trusted, &err);
    if (tap_ok(run(&g, 0, 64, 3, out, &err), "read the key's irradiance: %s", err.msg)) {
        const double axis[3] = {0, 0, 1};   /* the class of `normal`: +z */
        double want = ref_irradiance(&g.params, q, emitted, axis);
        tap_ok(fabs(out[7] - want) < 1e-4 * want, "irradiance about the class axis %.5g, "
               "emitted light included (host %.5g)", out[7], want);
    }

    for (int mode = 0; mode <= 1; mode++) {
        const char *what = mode ? "mixture" : "learned";
        if (!tap_ok(run(&g, mode, N, 7 + mode, out, &err), "%s: sample %u: %s", what, N, err.msg))
            continue;
        double *obs = calloc((size_t)HZ * HP, sizeof(double));
        double *exp_ = calloc((size_t)HZ * HP, sizeof(double));
        uint32_t bad_pdf = 0, bad_ref = 0, bad_len = 0;
        /* the GPU's bin probability is a difference of two float CDF values
         * (the way it samples): a few ulps of 1 off in absolute terms */
        const double cdf_ulps = 4 * 0x1p-24 * nb / (4 * PI);
        for (uint32_t i = 0; i < N; i++) {
            const float *o = out + 8 * (size_t)i;
            double w[3] = {o[0], o[1], o[2]};
            double len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            if (fabs(len - 1) > 1e-4)
                bad_len++;
            obs[hist_cell(w, HZ, HP)] += 1;
            double pq = ref_pdf(&g.params, qg, w), pb = lambert(w);
            if (mode == 0) {
                /* sampling and evaluation agree except on a bin edge */
                if (fabs(o[3] - o[4]) > 1e-4 * o[3])
                    bad_pdf++;
                if (fabs(o[4] - pq) > 1e-4 * pq + cdf_ulps)
                    bad_ref++;
            } else {
                double mix = m * o[4] + (1 - m) * o[5];
                if (fabs(o[3] - mix) > 1e-5 * mix)
                    bad_pdf++;
                if (fabs(o[4] - pq) > 1e-4 * pq + cdf_ulps || fabs(o[5] - pb) > 1e-4 * pb + 1e-6)
                    bad_ref++;
            }
        }
        tap_ok(bad_len == 0, "%s: directions are unit vectors (%u not)", what, bad_len);
        if (mode == 0)
            tap_ok(bad_pdf <= N / 1000, "learned: pdf at sampling equals pdf evaluated at w "
                   "(%u of %u differ, edge cases allowed: %u)", bad_pdf, N, N / 1000);
        else
            tap_ok(bad_pdf == 0, "mixture: pdf equals m pQ + (1-m) pBSDF for every sample "
                   "(%u differ)", bad_pdf);
        tap_ok(bad_ref <= N / 1000, "%s: GPU pdfs equal the host reference (%u of %u differ)",
               what, bad_ref, N);
        /* expected counts: exact for the piecewise-constant part, 8x8
         * midpoint quadrature per cell for the Lambertian lobe */
        for (uint32_t iz = 0; iz < HZ; iz++)
            for (uint32_t ip = 0; ip < HP; ip++) {
                double acc = 0;
                for (int a = 0; a < 8; a++)
                    for (int b = 0; b < 8; b++) {
                        double w[3];
                        grid_dir(iz, ip, (a + 0.5) / 8, (b + 0.5) / 8, HZ, HP, w);
                        double p = ref_pdf(&g.params, qg, w);
                        if (mode)
                            p = m * p + (1 - m) * lambert(w);
                        acc += p;
                    }
                exp_[(size_t)iz * HP + ip] = N * acc / 64 * (4 * PI / (HZ * HP));
            }
        rl_chi2_check(obs, exp_, HZ, HP, what);
        free(obs);
        free(exp_);
    }

    /* the pdfs integrate to 1: midpoint rule on a fine equal-area grid */
    if (tap_ok(run(&g, 2, QZ * QP, 0, out, &err), "evaluate on %ux%u directions: %s", QZ, QP,
               err.msg)) {
        double sq = 0, sm = 0, sq_ref = 0;
        for (uint32_t i = 0; i < QZ * QP; i++) {
            const float *v = inq + 4 * (size_t)i;
            double w[3] = {v[0], v[1], v[2]};
            sq += out[8 * (size_t)i];
            sm += out[8 * (size_t)i + 1];
            sq_ref += ref_pdf(&g.params, qg, w);
        }
        double dw = 4 * PI / (QZ * QP);
        tap_ok(fabs(sq * dw - 1) < 1e-3, "learned pdf integrates to %.6f (1 within 1e-3)", sq * dw);
        tap_ok(fabs(sq_ref * dw - 1) < 1e-3, "host reference integrates to %.6f", sq_ref * dw);
        tap_ok(fabs(sm * dw - 1) < 2e-3, "mixture pdf integrates to %.6f (1 within 2e-3)", sm * dw);
    }

    free(q);
    free(qg);
    free(emitted);
    free(out);
    free(inq);
    glDeleteTextures(1, &g.table_tex);
    glDeleteTextures(1, &g.guide_tex);
    cv_buffer_destroy(&g.ubo);
    cv_buffer_destroy(&g.table);
    cv_buffer_destroy(&g.guide);
    cv_buffer_destroy(&g.out);
    cv_buffer_destroy(&g.in);
}

int main(void)
{
    test_layout();
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    test_bins(gpu, 128, false);
    test_bins(gpu, 128, true);
    test_bins(gpu, 1000, false);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
