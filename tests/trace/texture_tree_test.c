/* texture_tree_test.c: composite texture trees in the shipped GLSL
 * (glsl/trace/bsdf/texture.glsl) against a recursive evaluation on the
 * host. Random trees (fixed seed) put scale, mix and checkerboard textures,
 * constants and 1x1 images in every operand position two deep, with
 * operands left to their constants and composites nested a third level
 * (read as their value_a, as texture.glsl documents): a value taken from
 * the wrong position of the walk, or left over from the operand walked
 * before, shows up as a wrong reflectance. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/rng.h"
#include "tests/trace/bsdf_probe.h"

enum { TREES = 48, MAX_TEX = 64 * TREES, QUERIES = 4 };

static uint32_t rng_state = 12345u;

static uint32_t rnd(uint32_t n)
{
    return (cv_test_lcg32_next(&rng_state) >> 8) % n;
}

/* k / 16 for k in [0, 16]: exact in half floats */
static float sixteenth(void) { return (float)rnd(17) / 16.0f; }

static uint16_t half_of(float f)
{
    /* f = k / 16, 0 <= k <= 16 */
    if (f == 0)
        return 0;
    int e = 0;
    float m = f;
    while (m < 1) {
        m *= 2;
        e--;
    }
    return (uint16_t)(((uint32_t)(e + 15) << 10) | (uint32_t)((m - 1) * 1024));
}

struct forest {
    CvTexture tex[MAX_TEX];
    uint32_t texels[2 * MAX_TEX];
    size_t n_tex, n_texels;
};

static cv_vec4 rand_rgb(void) { return (cv_vec4){sixteenth(), sixteenth(), sixteenth(), 1}; }

static int add_tex(struct forest *f, unsigned type)
{
    CvTexture *t = &f->tex[f->n_tex];
    memset(t, 0, sizeof(*t));
    t->type = type;
    t->tex_a = t->tex_b = t->amount_tex = -1;
    t->scale = 1;
    t->uv_map = (cv_vec4){1, 1, 0, 0};
    t->levels = 1;
    t->value_a = rand_rgb();
    t->value_b = rand_rgb();
    t->amount = sixteenth();
    return (int)f->n_tex++;
}

/* A random texture whose root sits at `depth` (0: the material's). */
static int grow(struct forest *f, int depth)
{
    uint32_t kind = rnd(depth < 3 ? 5 : 2);
    if (kind == 0)
        return add_tex(f, CV_TEX_CONSTANT);
    if (kind == 1) {
        int id = add_tex(f, CV_TEX_IMAGE);
        CvTexture *t = &f->tex[id];
        t->width = t->height = 1;
        t->offset = (uint32_t)f->n_texels;
        cv_vec4 c = rand_rgb();
        uint32_t *s = &f->texels[2 * f->n_texels++];
        s[0] = half_of(c.x) | ((uint32_t)half_of(c.y) << 16);
        s[1] = half_of(c.z) | ((uint32_t)half_of(1) << 16);
        if (rnd(4) == 0)
            t->flags |= CV_TEXF_FLOAT;
        return id;
    }
    static const unsigned types[3] = {CV_TEX_SCALE, CV_TEX_MIX, CV_TEX_CHECKERBOARD};
    int id = add_tex(f, types[kind - 2]);
    if (types[kind - 2] == CV_TEX_CHECKERBOARD)
        f->tex[id].uv_map = (cv_vec4){2, 2, 0, 0};
    if (rnd(3) == 0)
        f->tex[id].scale = 0.5f;
    int a = rnd(4) ? grow(f, depth + 1) : -1;
    int b = rnd(4) ? grow(f, depth + 1) : -1;
    int amt = rnd(3) ? grow(f, depth + 1) : -1;
    f->tex[id].tex_a = a;
    f->tex[id].tex_b = b;
    f->tex[id].amount_tex = amt;
    return id;
}

static float half_to_float(uint32_t h)
{
    return h ? ldexpf(1 + (h & 1023) / 1024.0f, (int)(h >> 10) - 15) : 0;
}

/* The documented semantics, recursively: composites below depth 2 read as
 * their value_a. */
static cv_vec4 eval(const struct forest *f, int id, int depth, float u, float v)
{
    const CvTexture *t = &f->tex[id];
    cv_vec4 r;
    if (t->type == CV_TEX_CONSTANT) {
        r = t->value_a;
    } else if (t->type == CV_TEX_IMAGE) {
        const uint32_t *s = &f->texels[2 * t->offset];
        r = (cv_vec4){half_to_float(s[0] & 0xffff), half_to_float(s[0] >> 16),
                      half_to_float(s[1] & 0xffff), 1};
        if (t->flags & CV_TEXF_FLOAT) {
            float m = (r.x + r.y + r.z) / 3;
            r = (cv_vec4){m, m, m, m};
        }
    } else if (depth >= 2) {
        return t->value_a;
    } else {
        cv_vec4 a = t->tex_a >= 0 ? eval(f, t->tex_a, depth + 1, u, v) : t->value_a;
        cv_vec4 b = t->tex_b >= 0 ? eval(f, t->tex_b, depth + 1, u, v) : t->value_b;
        float amt = t->amount_tex >= 0 ? eval(f, t->amount_tex, depth + 1, u, v).x : t->amount;
        if (t->type == CV_TEX_SCALE) {
            r = (cv_vec4){a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w};
        } else if (t->type == CV_TEX_MIX) {
            r = (cv_vec4){a.x + (b.x - a.x) * amt, a.y + (b.y - a.y) * amt, a.z + (b.z - a.z) * amt,
                          a.w + (b.w - a.w) * amt};
        } else {
            int c = (int)floorf(t->uv_map.x * u + t->uv_map.z) + (int)floorf(t->uv_map.y * v + t->uv_map.w);
            r = (c & 1) == 0 ? a : b;
        }
    }
    r.x *= t->scale;
    r.y *= t->scale;
    r.z *= t->scale;
    return r;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    static struct forest f;
    CvMaterial m[TREES];
    int roots[TREES];
    for (int i = 0; i < TREES; i++) {
        m[i] = probe_material(CV_MAT_DIFFUSE);
        /* most trees: a composite root with composites below */
        roots[i] = i % 8 == 0 ? grow(&f, 2) : grow(&f, 0);
        while (i % 8 != 0 && f.tex[roots[i]].type <= CV_TEX_IMAGE)
            roots[i] = grow(&f, 0);
        m[i].reflectance_tex = roots[i];
    }
    struct probe p;
    size_t n_texels = f.n_texels ? f.n_texels : 1;
    if (!tap_ok(probe_open_tex(gpu, &p, m, TREES, f.tex, f.n_tex, f.texels, n_texels, &err), "probe: %s",
                err.msg)) {
        cv_gpu_destroy(&gpu);
        return tap_done();
    }
    /* one point in each checker square of uv_map 2 */
    float q[4 * QUERIES] = {0.2f, 0.3f, 0, 0, 0.7f, 0.3f, 0, 0, 0.2f, 0.8f, 0, 0, 0.7f, 0.8f, 0, 0};
    float out[8 * QUERIES];
    int wrong = 0, first = -1;
    float worst = 0;
    for (int i = 0; i < TREES; i++) {
        if (!probe_run(&p, 2, (unsigned)i, (float[3]){0, 0, 1}, 0, q, QUERIES, out, &err)) {
            tap_ok(false, "tree %d: %s", i, err.msg);
            probe_close(&p);
            cv_gpu_destroy(&gpu);
            return tap_done();
        }
        for (int k = 0; k < QUERIES; k++) {
            cv_vec4 e = eval(&f, roots[i], 0, q[4 * k], q[4 * k + 1]);
            float want[3] = {fminf(fmaxf(e.x, 0), 1), fminf(fmaxf(e.y, 0), 1), fminf(fmaxf(e.z, 0), 1)};
            for (int c = 0; c < 3; c++) {
                float d = fabsf(out[8 * k + c] - want[c]);
                worst = fmaxf(worst, d);
                if (d > 1e-5f) {
                    wrong++;
                    if (first < 0)
                        first = i;
                }
            }
        }
    }
    tap_ok(f.n_tex > 4 * TREES, "the forest has %zu textures for %d trees", f.n_tex, TREES);
    tap_ok(wrong == 0, "%d trees x %d points: %d channels wrong (first in tree %d), largest difference %g",
           TREES, QUERIES, wrong, first, worst);
    probe_close(&p);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
