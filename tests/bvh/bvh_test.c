/* bvh_test.c: builds GPU BVHs over generated meshes (a clustered soup, a
 * height field with shared edges, a degenerate planar mesh full of equal
 * centroids, and 1-3 triangle meshes), with and without treelet
 * restructuring and leaf collapsing, reads each tree back and checks its
 * invariants and SAH cost (restructured below plain LBVH, within 10 % of a
 * CPU binned-SAH build), then traces ~100 000 rays through it and requires
 * closest hit (primitive and t) and any-hit to equal a GLSL brute force over
 * all triangles exactly; the brute force is itself compared with a CPU port
 * of the watertight test. Finally traverses a deliberately corrupt tree
 * (cycles, children out of range, leaves past the primitive buffer), which
 * must end rather than hang the GPU. Where the driver's advertised storage
 * block size is small (llvmpipe: 128 MiB), also a tree whose build nodes
 * pass it, traced against a CPU brute force. */
#include "config.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bvh/bvh.h"
#include "bvh/split.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "gpu/program.h"
#include "gpu/storage.h"
#include "tests/bvh/bvh_test_util.h"
#include "tests/gpu/gpu_test_util.h"

/* ---- rays ---- */

/* A float result in the subnormal range: GPUs that flush denormals to
 * zero (NVIDIA) compute it otherwise than the CPU. */
static bool subnormal(float x)
{
    return x != 0 && fabsf(x) < FLT_MIN;
}

/* x, after noting in *sub whether it is subnormal. */
static float note_subnormal(bool *sub, float x)
{
    *sub |= subnormal(x);
    return x;
}

/* CPU port of glsl/bvh/triangle.glsl, for the sanity check. *under (if
 * not NULL) is set when an intermediate float result is subnormal. */
static bool cpu_ray_tri(const float o[3], const float dir[3], const float *v0, const float *v1,
                        const float *v2, float *t_out, bool *under)
{
    bool sub = false;
#define CV_T(x) note_subnormal(&sub, (x))
    float ad[3] = {fabsf(dir[0]), fabsf(dir[1]), fabsf(dir[2])};
    int kz = ad[0] > ad[1] ? (ad[0] > ad[2] ? 0 : 2) : (ad[1] > ad[2] ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    if (dir[kz] < 0) {
        int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    float sx = CV_T(dir[kx] / dir[kz]), sy = CV_T(dir[ky] / dir[kz]), sz = CV_T(1.0f / dir[kz]);
    float a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
        a[k] = CV_T(v0[k] - o[k]);
        b[k] = CV_T(v1[k] - o[k]);
        c[k] = CV_T(v2[k] - o[k]);
    }
    float ax = CV_T(a[kx] - CV_T(sx * a[kz])), ay = CV_T(a[ky] - CV_T(sy * a[kz]));
    float bx = CV_T(b[kx] - CV_T(sx * b[kz])), by = CV_T(b[ky] - CV_T(sy * b[kz]));
    float cx = CV_T(c[kx] - CV_T(sx * c[kz])), cy = CV_T(c[ky] - CV_T(sy * c[kz]));
    float u = CV_T(CV_T(cx * by) - CV_T(cy * bx)), v = CV_T(CV_T(ax * cy) - CV_T(ay * cx));
    float w = CV_T(CV_T(bx * ay) - CV_T(by * ax));
    if (u == 0 || v == 0 || w == 0) {
        u = CV_T((float)((double)cx * by - (double)cy * bx));
        v = CV_T((float)((double)ax * cy - (double)ay * cx));
        w = CV_T((float)((double)bx * ay - (double)by * ax));
    }
    if (under)
        *under = sub;
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0))
        return false;
    float det = CV_T(CV_T(u + v) + w);
    if (det == 0) {
        if (under)
            *under = sub;
        return false;
    }
    float ta = CV_T(CV_T(sz * a[kz]) * u), tb = CV_T(CV_T(sz * b[kz]) * v);
    float tc = CV_T(CV_T(sz * c[kz]) * w);
    float t = CV_T(CV_T(CV_T(ta + tb) + tc) / det);
#undef CV_T
    if (under)
        *under = sub;
    *t_out = t;
    return isfinite(t);
}

/* The closest hit of ray r (o, tmin, d, tmax) by testing every triangle
 * on the CPU: its index (0xffffffff: none) and the bits of its t. Bit for
 * bit what the GLSL finds: the shader neither fuses (precise) nor divides
 * approximately (cv_div_rn), and C11 does not contract. */
static void cpu_closest(const struct mesh *m, const float *r, uint32_t *prim, uint32_t *t_bits)
{
    const float *o = r, *d = r + 4;
    float best = d[3];
    uint32_t bp = 0xffffffffu;
    for (uint32_t t = 0; t < m->nt; t++) {
        const uint32_t *ix = &m->t[t].idx.x;
        float tt;
        if (cpu_ray_tri(o, d, &m->v[ix[0]].pos_u.x, &m->v[ix[1]].pos_u.x, &m->v[ix[2]].pos_u.x,
                        &tt, NULL) &&
            tt > o[3] && tt < d[3] && (tt < best || (tt == best && t < bp))) {
            best = tt;
            bp = t;
        }
    }
    *prim = bp;
    memcpy(t_bits, &best, 4);
}

/* fast: the renderer's form of the triangle tests (CV_BVH_FAST_DIV);
 * bvh: the tree bound, whose stack size the program takes as the renderer's
 * do (NULL for a tree of the test's own). */
static bool trace(struct cv_gpu *gpu, const struct cv_bvh *bvh, bool brute, bool fast,
                  GLuint rays, GLuint results, uint32_t n_rays, uint32_t n_tris, uint32_t *out,
                  struct cv_error *err)
{
    const char *defs[4] = {NULL, NULL, NULL, NULL};
    int n_defs = 0;
    if (brute)
        defs[n_defs++] = "BRUTE_FORCE";
    if (fast)
        defs[n_defs++] = "CV_BVH_FAST_DIV";
    if (cv_bvh_stack_define(bvh))
        defs[n_defs++] = cv_bvh_stack_define(bvh);
    struct cv_program *p = cv_program_get(gpu, "bvh/rays_test.comp", n_defs ? defs : NULL, err);
    if (!p)
        return false;
    cv_buffer_bind(rays, CV_BIND_PROBE_IN);
    cv_buffer_bind(results, CV_BIND_PROBE_OUT);
    glProgramUniform1ui(p->id, glGetUniformLocation(p->id, "u_n_rays"), n_rays);
    glProgramUniform1ui(p->id, glGetUniformLocation(p->id, "u_n_tris"), n_tris);
    cv_program_dispatch_1d(p, n_rays);
    return cv_buffer_read(results, 0, (size_t)n_rays * 16, out, err);
}

/* Makes n_rays rays over the mesh into `rays` (8 floats each) and their
 * GPU buffer *rb, a result buffer *res, and binds the mesh and tree. With
 * `from`, half the rays start there (make_rays_from). */
static bool rays_setup(const struct mesh *m, const struct cv_bvh *bvh, GLuint vb, GLuint tb,
                       uint32_t n_rays, const float *from, float *rays, GLuint *rb, GLuint *res,
                       struct cv_error *err)
{
    make_rays(m, rays, n_rays);
    if (from)
        make_rays_from(m, from, rays, n_rays / 2);
    *rb = cv_buffer_create((size_t)n_rays * 32, rays, "rays", err);
    *res = cv_buffer_create((size_t)n_rays * 16, NULL, "ray results", err);
    cv_buffer_bind(vb, CV_BIND_VERTICES);
    cv_buffer_bind(tb, CV_BIND_TRIANGLES);
    cv_bvh_bind(bvh);
    return *rb && *res;
}

/* Whether triangle `prim` is so small that products of its edges (the
 * ray-triangle test's cross products) are below the normal float range. */
/* Whether ray r's test against triangle prim has a subnormal intermediate
 * on the CPU: a GPU that flushes denormals may hit or miss it otherwise. */
static bool ray_underflows(const struct mesh *m, const float *r, uint32_t prim)
{
    if (prim >= m->nt)
        return false;
    const uint32_t *ix = &m->t[prim].idx.x;
    float t;
    bool under = false;
    cpu_ray_tri(r, r + 4, &m->v[ix[0]].pos_u.x, &m->v[ix[1]].pos_u.x, &m->v[ix[2]].pos_u.x, &t,
                &under);
    return under;
}

static void check_rays(struct cv_gpu *gpu, const char *name, const struct mesh *m,
                       const struct cv_bvh *bvh, GLuint vb, GLuint tb, uint32_t n_rays,
                       const float *from)
{
    struct cv_error err = {{0}};
    float *rays = malloc((size_t)n_rays * 32);
    uint32_t *got = malloc((size_t)n_rays * 16), *want = malloc((size_t)n_rays * 16);
    GLuint rb = 0, res = 0;
    bool ok = rays_setup(m, bvh, vb, tb, n_rays, from, rays, &rb, &res, &err) &&
              trace(gpu, bvh, false, false, rb, res, n_rays, m->nt, got, &err) &&
              trace(gpu, bvh, true, false, rb, res, n_rays, m->nt, want, &err);
    if (!tap_ok(ok, "%s: %u rays traced: %s", name, n_rays, ok ? "yes" : err.msg))
        goto out;
    uint32_t bad_hit = 0, bad_any = 0, hits = 0, first = 0, steps = 0;
    for (uint32_t i = 0; i < n_rays; i++) {
        const uint32_t *g = &got[4 * i], *w = &want[4 * i];
        steps = g[3] > steps ? g[3] : steps;
        hits += w[1] != 0xffffffffu;
        if ((g[1] != w[1] || (w[1] != 0xffffffffu && g[0] != w[0])) && bad_hit++ < 3) {
            float gt, wt;
            memcpy(&gt, &g[0], 4);
            memcpy(&wt, &w[0], 4);
            tap_diag("ray %u: o (%g %g %g) d (%g %g %g) [%g, %g]: bvh prim %d t %.9g, brute prim %d t %.9g",
                     i, rays[8 * i], rays[8 * i + 1], rays[8 * i + 2], rays[8 * i + 4],
                     rays[8 * i + 5], rays[8 * i + 6], rays[8 * i + 3], rays[8 * i + 7],
                     (int)g[1], gt, (int)w[1], wt);
            if (bad_hit == 1)
                first = i;
        }
        bad_any += g[2] != w[2] || w[2] != (w[1] != 0xffffffffu);
    }
    tap_ok(bad_hit == 0, "%s: closest hit equals brute force (%u of %u rays differ, first %u; "
           "%u hits)", name, bad_hit, n_rays, first, hits);
    tap_ok(bad_any == 0, "%s: any-hit equals brute force (%u differ)", name, bad_any);
    /* Each query visits a node at most once (a revisit would be a loop that
     * llvmpipe cuts short but a real GPU does not). */
    uint32_t n_nodes = cv_bvh_stats(bvh)->n_nodes;
    tap_ok(steps <= 2 * n_nodes, "%s: at most %u nodes visited per ray (tree has %u)", name, steps,
           n_nodes);

    /* CPU sanity check of the GLSL brute force on the first rays. Rays whose
     * test against the closest hit of either has a subnormal intermediate
     * (the deep tree's innermost clusters) are left out: GPUs that flush
     * denormals to zero (NVIDIA) see those triangles otherwise than the
     * CPU, for brute force and traversal alike. */
    uint32_t n_cpu = n_rays < 1500 ? n_rays : 1500, agree = 0, tiny = 0;
    for (uint32_t i = 0; i < n_cpu; i++) {
        uint32_t bp, best_bits;
        cpu_closest(m, &rays[8 * i], &bp, &best_bits);
        if (bp == want[4 * i + 1] && (bp == 0xffffffffu || want[4 * i] == best_bits))
            agree++;
        else if (ray_underflows(m, &rays[8 * i], bp) ||
                 ray_underflows(m, &rays[8 * i], want[4 * i + 1]))
            tiny++;
        else if (i + 1 - agree - tiny <= 3)
            tap_diag("ray %u: GLSL prim %d t %08x, CPU prim %d t %08x", i, (int)want[4 * i + 1],
                     want[4 * i], (int)bp, best_bits);
    }
    tap_ok(agree + tiny == n_cpu,
           "%s: GLSL brute force agrees with the CPU bit for bit on %u of %u rays (%u left out: "
           "subnormal intermediates)", name, agree, n_cpu - tiny, tiny);

    /* The renderer traces with the driver's division and a division-free
     * any-hit test: traversal must still find what brute force finds with
     * the same tests. */
    ok = trace(gpu, bvh, false, true, rb, res, n_rays, m->nt, got, &err) &&
         trace(gpu, bvh, true, true, rb, res, n_rays, m->nt, want, &err);
    uint32_t bad_fast = 0;
    for (uint32_t i = 0; ok && i < n_rays; i++) {
        const uint32_t *g = &got[4 * i], *w = &want[4 * i];
        bad_fast += g[1] != w[1] || (w[1] != 0xffffffffu && g[0] != w[0]) || g[2] != w[2];
    }
    tap_ok(ok && bad_fast == 0,
           "%s: renderer's triangle tests: closest and any-hit equal brute force (%u of %u "
           "rays differ)%s%s", name, bad_fast, n_rays, ok ? "" : ": ", ok ? "" : err.msg);
out:
    cv_buffer_destroy(&rb);
    cv_buffer_destroy(&res);
    free(rays);
    free(got);
    free(want);
}

/* The build counts the wide tree's levels and the most stack entries a
 * query can need in it (bvh.c sizes the stack from that): both as the
 * read-back tree has them, and the tree fits the stack it is traced with,
 * which is the default unless the tree needs more. */
static void check_stack(const char *name, const struct cv_bvh *bvh, const struct tree_info *ti)
{
    const struct cv_bvh_stats *s = cv_bvh_stats(bvh);
    const char *def = cv_bvh_stack_define(bvh);
    char want[32] = "";
    if (s->stack_size > CV_BVH_STACK_SIZE)
        snprintf(want, sizeof(want), "CV_BVH_STACK_SIZE=%u", s->stack_size);
    tap_ok(s->depth == (uint32_t)ti->wide_depth && s->stack_need == (uint32_t)ti->stack_need &&
           (uint32_t)ti->stack_need <= s->stack_size && s->stack_size >= CV_BVH_STACK_SIZE &&
           (s->stack_size == CV_BVH_STACK_SIZE || s->stack_size < (uint32_t)ti->stack_need + 16) &&
           strcmp(def ? def : "", want) == 0,
           "%s: wide depth %d, %d stack entries at most (the build's counts: %u, %u; the stack "
           "holds %u, define %s)", name, ti->wide_depth, ti->stack_need, s->depth, s->stack_need,
           s->stack_size, def ? def : "none");
}

/* Widening's result depends neither on how many levels run per read-back
 * nor on the order its atomics hand out queue entries (src/bvh/widen.h):
 * two builds of one mesh, one a level per read-back, give the same bytes. */
static void check_same_tree(const char *name, const struct cv_bvh *a, const struct cv_bvh *b)
{
    struct cv_error err = {{0}};
    uint32_t na = cv_bvh_stats(a)->n_nodes, nb = cv_bvh_stats(b)->n_nodes;
    size_t bytes = (size_t)na * sizeof(CvBvhNode4);
    void *ta = malloc(bytes), *tb = malloc(bytes);
    bool ok = na == nb && cv_buffer_read(cv_bvh_nodes_buffer(a), 0, bytes, ta, &err) &&
              cv_buffer_read(cv_bvh_nodes_buffer(b), 0, bytes, tb, &err);
    tap_ok(ok && memcmp(ta, tb, bytes) == 0,
           "%s: widened a level per read-back, the same wide tree (%u and %u nodes, depth %u)%s%s",
           name, na, nb, cv_bvh_stats(b)->depth, err.msg[0] ? ": " : "", err.msg);
    free(ta);
    free(tb);
}

/* A tree that needs more traversal stack than CV_BVH_STACK_SIZE: more
 * treelet rounds deepen mesh_geometric's tree further. Every ray must still
 * find what brute force finds. */
static void check_deep(struct cv_gpu *gpu)
{
    struct cv_error err = {{0}};
    struct mesh m;
    mesh_geometric(&m, 150, 16, 0.7);
    GLuint vb = 0, tb = 0;
    struct cv_bvh_params params = cv_bvh_default_params();
    params.split_budget = 0;
    params.keep_binary = true;
    params.treelet_rounds = 12;
    struct cv_bvh *bvh = NULL;
    bool ok = tap_ok(mesh_upload(&m, &vb, &tb, &err), "deep tree: uploaded %u triangles", m.nt) &&
              tap_ok(cv_bvh_build(gpu, vb, tb, m.nt, &params, &bvh, &err), "deep tree: built%s%s",
                     bvh ? "" : ": ", bvh ? "" : err.msg);
    if (ok) {
        const struct cv_bvh_stats *s = cv_bvh_stats(bvh);
        struct tree_info ti = check_tree(&m, bvh);
        tap_ok(ti.ok, "deep tree: invariants hold (%u wide nodes, depth %d) %s", s->n_nodes,
               ti.wide_depth, ti.why);
        tap_ok(s->stack_need > CV_BVH_STACK_SIZE,
               "deep tree: needs %u stack entries, more than the default %d", s->stack_need,
               CV_BVH_STACK_SIZE);
        check_stack("deep tree", bvh, &ti);
        /* From beyond the shallow end of the axis: a ray to a triangle deep
         * down enters every cluster's box on the way and pushes them all. */
        const float from[3] = {-1.0e-25f, 0.0f, 0.0f};
        check_rays(gpu, "deep tree", &m, bvh, vb, tb, 16000, from);
    }
    cv_bvh_destroy(&bvh);
    cv_buffer_destroy(&vb);
    cv_buffer_destroy(&tb);
    mesh_free(&m);
}

static void check_mesh(struct cv_gpu *gpu, const char *name, struct mesh *m, uint32_t n_rays,
                       bool check_sah)
{
    struct cv_error err = {{0}};
    GLuint vb = 0, tb = 0;
    if (!tap_ok(mesh_upload(m, &vb, &tb, &err), "%s: uploaded %u triangles", name, m->nt))
        return;
    /* Without splitting: every triangle exactly once (check_split covers
     * splitting, whatever the default). */
    struct cv_bvh_params params = cv_bvh_default_params();
    params.split_budget = 0;
    params.keep_binary = true;
    struct cv_bvh_params lbvh_params = params;
    lbvh_params.treelet_rounds = 0;
    /* The same tree again, widened one level per read-back. */
    struct cv_bvh_params step_params = params;
    step_params.widen_levels = 1;
    struct cv_bvh *bvh = NULL, *lbvh = NULL, *step = NULL;
    bool built = cv_bvh_build(gpu, vb, tb, m->nt, &params, &bvh, &err) &&
                 cv_bvh_build(gpu, vb, tb, m->nt, &lbvh_params, &lbvh, &err) &&
                 cv_bvh_build(gpu, vb, tb, m->nt, &step_params, &step, &err);
    if (tap_ok(built, "%s: built (restructured and plain LBVH): %s", name, built ? "yes" : err.msg)) {
        const struct cv_bvh_stats *s = cv_bvh_stats(bvh), *sl = cv_bvh_stats(lbvh);
        struct tree_info ti = check_tree(m, bvh), tl = check_tree(m, lbvh);
        tap_ok(ti.ok, "%s: restructured tree invariants hold (%u binary nodes, depth %d; %u wide, "
               "depth %d) %s", name, s->n_binary_nodes, ti.depth, s->n_nodes, ti.wide_depth, ti.why);
        tap_ok(tl.ok, "%s: LBVH tree invariants hold (%u binary nodes, depth %d; %u wide, depth "
               "%d) %s", name, sl->n_binary_nodes, tl.depth, sl->n_nodes, tl.wide_depth, tl.why);
        check_stack(name, bvh, &ti);
        check_same_tree(name, bvh, step);
        if (m->nt >= 2)
            tap_ok(fabs(ti.sah - s->sah_cost) <= 1e-3 * ti.sah + 1e-6,
                   "%s: GPU SAH %.4f equals the read-back tree's %.4f", name, s->sah_cost, ti.sah);
        if (check_sah) {
            double ref = ref_sah(m);
            tap_ok(ti.sah < tl.sah, "%s: SAH after restructuring %.4f < LBVH %.4f", name, ti.sah,
                   tl.sah);
            tap_ok(ti.sah <= 1.10 * ref, "%s: SAH %.4f within 10%% of CPU binned SAH %.4f (%+.1f%%)",
                   name, ti.sah, ref, 100.0 * (ti.sah / ref - 1));
        }
        tap_diag("%s: %.1f bytes/triangle, %u nodes", name, (double)s->bytes / (m->nt ? m->nt : 1),
                 s->n_nodes);
        check_rays(gpu, name, m, bvh, vb, tb, n_rays, NULL);
    }
    /* Without collapsing every leaf holds one triangle: n - 1 nodes. */
    struct cv_bvh_params flat = params;
    flat.collapse_leaves = false;
    struct cv_bvh *fb = NULL;
    if (m->nt >= 2 && tap_ok(cv_bvh_build(gpu, vb, tb, m->nt, &flat, &fb, &err),
                             "%s: built without leaf collapsing: %s", name, fb ? "yes" : err.msg)) {
        struct tree_info tf = check_tree(m, fb);
        tap_ok(tf.ok && cv_bvh_stats(fb)->n_binary_nodes == m->nt - 1,
               "%s: uncollapsed tree valid with %u binary nodes for %u triangles (%u wide) %s",
               name, cv_bvh_stats(fb)->n_binary_nodes, m->nt, cv_bvh_stats(fb)->n_nodes, tf.why);
    }
    cv_bvh_destroy(&fb);
    cv_bvh_destroy(&bvh);
    cv_bvh_destroy(&lbvh);
    cv_bvh_destroy(&step);
    tap_ok(bvh == NULL, "%s: destroy clears the pointer", name);
    cv_buffer_destroy(&vb);
    cv_buffer_destroy(&tb);
}

/* Triangle splitting (src/bvh/split.h) with `budget`: first the references
 * themselves (every triangle referenced, no more extra references than the
 * budget, every box inside its triangle's box, the boxes of a triangle's
 * references covering it), then a tree over them, read back and traced
 * against brute force. */
static void check_split(struct cv_gpu *gpu, const char *name, struct mesh *m, float budget,
                        uint32_t n_rays)
{
    struct cv_error err = {{0}};
    GLuint vb = 0, tb = 0, boxes = 0;
    uint32_t nt = m->nt, n_refs = 0;
    if (!tap_ok(mesh_upload(m, &vb, &tb, &err), "%s: uploaded %u triangles", name, nt))
        return;
    uint32_t allowed = (uint32_t)((double)budget * nt);
    struct cv_bvh_split *sp = cv_bvh_split_create(gpu, nt, allowed, &err);
    bool ok = sp && cv_bvh_split_count(sp, vb, tb, &n_refs, &err) &&
              (boxes = cv_buffer_create((size_t)n_refs * 32, NULL, "ref boxes", &err)) &&
              cv_bvh_split_emit(sp, boxes, &err);
    float (*rb)[8] = malloc((n_refs ? n_refs : 1) * sizeof(*rb));
    uint32_t *rt = malloc((n_refs ? n_refs : 1) * 4);
    ok = ok && cv_buffer_read(boxes, 0, (size_t)n_refs * 32, rb, &err) &&
         cv_buffer_read(cv_bvh_split_ref_tris(sp), 0, (size_t)n_refs * 4, rt, &err);
    if (tap_ok(ok, "%s: split with budget %g: %s", name, budget, ok ? "yes" : err.msg)) {
        tap_ok(n_refs >= nt && n_refs - nt <= allowed,
               "%s: %u extra references, at most the budget's %u", name, n_refs - nt, allowed);
        /* Each triangle's references, gathered; the first n are in order. */
        uint32_t bad_tri = 0, bad_box = 0, bad_cover = 0, *count = calloc(nt + 1, 4);
        double ref_area = 0, tri_area = 0, miss[3] = {0, 0, 0};
        for (uint32_t r = 0; r < n_refs; r++) {
            if (rt[r] >= nt || (r < nt && rt[r] != r)) {
                bad_tri++;
                continue;
            }
            count[rt[r] + 1]++;
            float tlo[3], thi[3];
            tri_box(m, rt[r], tlo, thi);
            bad_box += !(rb[r][0] <= rb[r][4] && rb[r][1] <= rb[r][5] && rb[r][2] <= rb[r][6]) ||
                       !box_in(&rb[r][0], &rb[r][4], tlo, thi);
        }
        for (uint32_t t = 0; t < nt; t++)
            count[t + 1] += count[t];
        float (*by_tri)[6] = malloc((n_refs ? n_refs : 1) * sizeof(*by_tri));
        uint32_t *fill = calloc(nt + 1, 4);
        for (uint32_t r = 0; bad_tri == 0 && r < n_refs; r++) {
            float *dst = by_tri[count[rt[r]] + fill[rt[r]]++];
            memcpy(dst, &rb[r][0], 12);
            memcpy(dst + 3, &rb[r][4], 12);
        }
        for (uint32_t t = 0; bad_tri == 0 && t < nt; t++) {
            uint32_t k = count[t + 1] - count[t];
            if (k < 2)
                continue;
            float tlo[3], thi[3];
            tri_box(m, t, tlo, thi);
            tri_area += half_area3(tlo, thi);
            for (uint32_t j = 0; j < k; j++)
                ref_area += half_area3(by_tri[count[t] + j], by_tri[count[t] + j] + 3);
            if (!tri_covered(m, t, by_tri + count[t], k, 24, miss) && bad_cover++ == 0)
                tap_diag("triangle %u: point (%.9g %.9g %.9g) outside its %u references' boxes", t,
                         miss[0], miss[1], miss[2], k);
        }
        tap_ok(bad_tri == 0, "%s: every triangle referenced, reference r < n is triangle r "
               "(%u wrong)", name, bad_tri);
        tap_ok(bad_box == 0, "%s: every reference's box lies inside its triangle's (%u outside)",
               name, bad_box);
        tap_ok(bad_cover == 0, "%s: the references' boxes cover their triangle (%u not)", name,
               bad_cover);
        tap_ok(n_refs == nt || ref_area < tri_area,
               "%s: split triangles' reference boxes are smaller: area %.4g of %.4g", name,
               ref_area, tri_area);
        free(count);
        free(fill);
        free(by_tri);
    }
    cv_bvh_split_destroy(&sp);
    tap_ok(sp == NULL, "%s: split destroy clears the pointer", name);
    cv_buffer_destroy(&boxes);
    free(rb);
    free(rt);

    struct cv_bvh_params params = cv_bvh_default_params(), off = params;
    params.split_budget = budget;
    params.keep_binary = true;
    off.split_budget = 0;
    struct cv_bvh *bvh = NULL, *plain = NULL;
    bool built = cv_bvh_build(gpu, vb, tb, nt, &params, &bvh, &err) &&
                 cv_bvh_build(gpu, vb, tb, nt, &off, &plain, &err);
    if (tap_ok(built, "%s: built with splitting %g: %s", name, budget, built ? "yes" : err.msg)) {
        const struct cv_bvh_stats *s = cv_bvh_stats(bvh);
        struct tree_info ti = check_tree(m, bvh);
        tap_ok(ti.ok && s->n_refs == n_refs,
               "%s: split tree invariants hold (%u references, %u wide nodes, depth %d) %s", name,
               s->n_refs, s->n_nodes, ti.wide_depth, ti.why);
        check_stack(name, bvh, &ti);
        tap_ok(fabs(ti.sah - s->sah_cost) <= 1e-3 * ti.sah + 1e-6,
               "%s: GPU SAH %.4f equals the read-back tree's %.4f", name, s->sah_cost, ti.sah);
        tap_diag("%s: SAH %.4f split, %.4f not; %.1f bytes/triangle", name, s->sah_cost,
                 cv_bvh_stats(plain)->sah_cost, (double)s->bytes / nt);
        check_rays(gpu, name, m, bvh, vb, tb, n_rays, NULL);
    }
    cv_bvh_destroy(&bvh);
    cv_bvh_destroy(&plain);
    cv_buffer_destroy(&vb);
    cv_buffer_destroy(&tb);
}

/* One CvBvhNode4 child: box, word, count. */
static void set_child(CvBvhNode4 *nd, int slot, float lo, float hi, int32_t word, int32_t count)
{
    cv_vec4 *v[6] = {&nd->lox, &nd->loy, &nd->loz, &nd->hix, &nd->hiy, &nd->hiz};
    for (int k = 0; k < 6; k++)
        (&v[k]->x)[slot] = k < 3 ? lo : hi;
    (&nd->word.x)[slot] = word;
    (&nd->count.x)[slot] = count;
}

static void check_corrupt(struct cv_gpu *gpu)
{
    struct cv_error err = {{0}};
    struct mesh m;
    mesh_soup(&m, 3);
    const float big = 1.0e30f;
    CvBvhNode4 nodes[4];
    /* Root: an inner child, a leaf running far past the primitives, the
     * root as its own child and a leaf at a negative slot; node 1 points
     * at itself (a cycle, twice) and node 2; node 2 at node 3, beyond the
     * array and below 0, with a leaf whose end overflows; node 3 has
     * garbage words and counts. */
    set_child(&nodes[0], 0, -big, big, 1, 0);
    set_child(&nodes[0], 1, -big, big, 0, 1000);
    set_child(&nodes[0], 2, -big, big, 0, 0);
    set_child(&nodes[0], 3, -big, big, -5, 3);
    set_child(&nodes[1], 0, -big, big, 1, 0);
    set_child(&nodes[1], 1, -big, big, 2, 0);
    set_child(&nodes[1], 2, -big, big, 1, 0);
    set_child(&nodes[1], 3, -big, big, 1 << 30, 1 << 29);
    set_child(&nodes[2], 0, -big, big, 3, 0);
    set_child(&nodes[2], 1, -big, big, 77, 0);
    set_child(&nodes[2], 2, -big, big, -1, 0);
    set_child(&nodes[2], 3, -big, big, 1, 0x7fffffff);
    set_child(&nodes[3], 0, -big, big, -5, -3);
    set_child(&nodes[3], 1, -big, big, 1 << 30, 1 << 29);
    set_child(&nodes[3], 2, -big, big, 0x7fffffff, 5);
    set_child(&nodes[3], 3, -big, big, 2, -1);
    uint32_t prims[2] = {99999, 0};
    uint32_t n_rays = 256;
    float *rays = malloc((size_t)n_rays * 32);
    uint32_t *got = malloc((size_t)n_rays * 16);
    make_rays(&m, rays, n_rays);
    GLuint vb = 0, tb = 0, lt = 0;
    GLuint nb = cv_buffer_create(sizeof(nodes), nodes, "corrupt nodes", &err);
    GLuint pb = nb ? cv_buffer_create(sizeof(prims), prims, "corrupt prims", &err) : 0;
    GLuint rb = pb ? cv_buffer_create((size_t)n_rays * 32, rays, "rays", &err) : 0;
    GLuint res = rb ? cv_buffer_create((size_t)n_rays * 16, NULL, "ray results", &err) : 0;
    bool ok = res && mesh_upload(&m, &vb, &tb, &err) &&
              (lt = cv_bvh_leaf_tris_create(gpu, vb, tb, pb, 2, &err)) != 0;
    if (ok) {
        cv_buffer_bind(vb, CV_BIND_VERTICES);
        cv_buffer_bind(tb, CV_BIND_TRIANGLES);
        cv_buffer_bind(nb, CV_BIND_BVH_NODES);
        cv_buffer_bind(pb, CV_BIND_BVH_PRIMS);
        cv_buffer_bind(lt, CV_BIND_BVH_TRIS);
        ok = trace(gpu, NULL, false, false, rb, res, n_rays, m.nt, got, &err);
    }
    tap_ok(ok, "corrupt tree: %u rays traced and ended: %s", n_rays, ok ? "yes" : err.msg);
    uint32_t bad = 0, steps = 0;
    for (uint32_t i = 0; ok && i < n_rays; i++) {
        bad += got[4 * i + 1] != 0xffffffffu && got[4 * i + 1] != 0;
        steps = got[4 * i + 3] > steps ? got[4 * i + 3] : steps;
    }
    tap_ok(ok && bad == 0, "corrupt tree: only the one real primitive is ever hit (%u others)", bad);
    /* llvmpipe ends endless loops itself after 65535 rounds, so only the
     * step count shows a missing bound there: closest + any-hit, 4 nodes. */
    tap_ok(ok && steps <= 8, "corrupt tree: at most %u nodes visited per ray (8 allowed)", steps);
    cv_buffer_destroy(&vb);
    cv_buffer_destroy(&tb);
    cv_buffer_destroy(&nb);
    cv_buffer_destroy(&pb);
    cv_buffer_destroy(&lt);
    cv_buffer_destroy(&rb);
    cv_buffer_destroy(&res);
    free(rays);
    free(got);
    mesh_free(&m);
}

/* Traversal against the CPU's brute force: llvmpipe ends a shader loop
 * after 65535 iterations, so the GLSL brute force cannot test a mesh of
 * more triangles than that. */
static void check_large_rays(struct cv_gpu *gpu, const char *name, const struct mesh *m,
                             const struct cv_bvh *bvh, GLuint vb, GLuint tb, uint32_t n_rays)
{
    struct cv_error err = {{0}};
    float *rays = malloc((size_t)n_rays * 32);
    uint32_t *got = malloc((size_t)n_rays * 16);
    GLuint rb = 0, res = 0;
    bool ok = rays_setup(m, bvh, vb, tb, n_rays, NULL, rays, &rb, &res, &err) &&
              trace(gpu, bvh, false, false, rb, res, n_rays, m->nt, got, &err);
    uint32_t bad = 0, hits = 0;
    for (uint32_t i = 0; ok && i < n_rays; i++) {
        uint32_t prim, t_bits;
        cpu_closest(m, &rays[8 * i], &prim, &t_bits);
        hits += prim != 0xffffffffu;
        const uint32_t *g = &got[4 * i];
        if ((g[1] != prim || (prim != 0xffffffffu && g[0] != t_bits) ||
             g[2] != (prim != 0xffffffffu)) &&
            bad++ < 3)
            tap_diag("ray %u: bvh prim %d t %08x any %u, CPU prim %d t %08x", i, (int)g[1], g[0],
                     g[2], (int)prim, t_bits);
    }
    tap_ok(ok && bad == 0,
           "%s: closest and any-hit equal the CPU's brute force (%u of %u rays differ, %u "
           "hits)%s%s",
           name, bad, n_rays, hits, ok ? "" : ": ", ok ? "" : err.msg);
    cv_buffer_destroy(&rb);
    cv_buffer_destroy(&res);
    free(rays);
    free(got);
}

/* A tree whose build nodes (2 n of 48 bytes) pass the driver's advertised
 * storage block size. Where the driver addresses more than it advertises
 * (llvmpipe says 128 MiB: gpu/storage.h probes), build and traversal must
 * still be right. One round of 5-leaf treelets keeps llvmpipe's time down
 * (an order of magnitude below the default's); few rays, as each
 * brute-force ray tests every triangle on the CPU. */
static void check_large(struct cv_gpu *gpu)
{
    long long limit = gpu->info.max_ssbo_bytes;
    if (limit <= 0 || limit > (256LL << 20)) {
        tap_ok(true, "# SKIP the driver advertises %lld bytes per storage buffer: a tree beyond "
                     "that is too large for a test", limit);
        return;
    }
    struct cv_error err = {{0}};
    struct mesh m;
    mesh_soup(&m, (uint32_t)(limit / (2 * sizeof(CvBvhBuildNode))) + 20000);
    char name[64];
    snprintf(name, sizeof(name), "%u triangles (beyond %lld MiB)", m.nt, limit >> 20);
    GLuint vb = 0, tb = 0;
    struct cv_bvh_params params = cv_bvh_default_params();
    params.split_budget = 0;
    params.treelet_rounds = 1;
    params.treelet_size = 5;
    params.keep_binary = true;
    struct cv_bvh *bvh = NULL;
    bool built = mesh_upload(&m, &vb, &tb, &err) &&
                 cv_bvh_build(gpu, vb, tb, m.nt, &params, &bvh, &err);
    if (tap_ok(built, "%s: built: %s", name, built ? "yes" : err.msg)) {
        struct tree_info ti = check_tree(&m, bvh);
        tap_ok(ti.ok && gpu->storage.works > (uint64_t)limit,
               "%s: tree invariants hold, build nodes in %.0f MiB (probed) %s", name,
               gpu->storage.works / 1048576.0, ti.why);
        check_large_rays(gpu, name, &m, bvh, vb, tb, 100);
    }
    cv_bvh_destroy(&bvh);
    cv_buffer_destroy(&vb);
    cv_buffer_destroy(&tb);
    mesh_free(&m);
}

/* The tree's own buffers go back to the GPU's pool when it is destroyed
 * (bvh/bvh.c): another build of the same mesh makes no new buffer, and a
 * tree over fewer triangles, built into the larger buffers, still traces
 * as brute force does (its buffers are bound as the ranges it uses; its
 * leaf triangles are written in several passes, bvh.c). */
static void check_reuse(struct cv_gpu *gpu)
{
    struct cv_error err = {{0}};
    struct mesh m;
    mesh_soup(&m, 4000);
    GLuint vb = 0, tb = 0, vb2 = 0, tb2 = 0;
    struct cv_bvh *bvh = NULL;
    /* From an empty pool, as a process's first build: the earlier checks'
     * leftovers would be handed out in their place (scene upload settles
     * the pool after every build, trace/scene_upload.c). */
    cv_buffer_pool_trim(gpu->scratch);
    bool ok = mesh_upload(&m, &vb, &tb, &err) && cv_bvh_build(gpu, vb, tb, m.nt, NULL, &bvh, &err);
    cv_bvh_destroy(&bvh);
    size_t made = cv_buffer_pool_created(gpu->scratch);
    ok = ok && cv_bvh_build(gpu, vb, tb, m.nt, NULL, &bvh, &err);
    size_t again = cv_buffer_pool_created(gpu->scratch);
    tap_ok(ok && again == made, "reuse: another build of the same mesh makes no new buffer "
           "(%zu made before it, %zu after)%s%s", made, again, ok ? "" : ": ", ok ? "" : err.msg);
    cv_bvh_destroy(&bvh);

    /* That tree's leaf triangles also go in passes of 1000 slots. */
    m.nt = 3900;
    struct cv_bvh_params passes = cv_bvh_default_params();
    passes.leaf_tris_window = 1000;
    ok = mesh_upload(&m, &vb2, &tb2, &err) &&
         cv_bvh_build(gpu, vb2, tb2, m.nt, &passes, &bvh, &err);
    GLint64 held = 0;
    if (ok)
        glGetNamedBufferParameteri64v(cv_bvh_nodes_buffer(bvh), GL_BUFFER_SIZE, &held);
    uint64_t used = ok ? (uint64_t)cv_bvh_stats(bvh)->n_nodes * sizeof(CvBvhNode4) : 0;
    tap_ok(ok && cv_buffer_pool_created(gpu->scratch) == again && (uint64_t)held > used,
           "reuse: 3900 triangles' tree built in the 4000's buffers (nodes: %llu of %lld bytes)",
           (unsigned long long)used, (long long)held);
    if (ok)
        check_rays(gpu, "reuse, 3900 of 4000", &m, bvh, vb2, tb2, 8000, NULL);
    m.nt = 4000;
    cv_bvh_destroy(&bvh);
    cv_buffer_destroy(&vb);
    cv_buffer_destroy(&tb);
    cv_buffer_destroy(&vb2);
    cv_buffer_destroy(&tb2);
    mesh_free(&m);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct mesh m;
    mesh_soup(&m, 4000);
    check_mesh(gpu, "clustered soup", &m, 32000, true);
    mesh_free(&m);
    check_reuse(gpu);
    mesh_grid(&m, 40);
    check_mesh(gpu, "height field", &m, 32000, true);
    mesh_free(&m);
    mesh_planar(&m, 3000);
    check_mesh(gpu, "planar duplicates", &m, 32000, true);
    mesh_free(&m);
    mesh_cones(&m, 60, 48);
    check_mesh(gpu, "cones", &m, 16000, false);
    check_split(gpu, "cones, split 0.3", &m, 0.3f, 16000);
    check_split(gpu, "cones, split 2", &m, 2.0f, 16000);
    mesh_free(&m);
    mesh_planar(&m, 3000);
    check_split(gpu, "planar duplicates, split 0.3", &m, 0.3f, 16000);
    mesh_free(&m);
    mesh_fans(&m, 60, 40);
    check_split(gpu, "planar fans, split 0.5", &m, 0.5f, 16000);
    mesh_free(&m);
    mesh_soup(&m, 4000);
    check_split(gpu, "clustered soup, split 0.3", &m, 0.3f, 16000);
    mesh_free(&m);
    for (uint32_t n = 2; n <= 3; n++) {
        char name[48];
        snprintf(name, sizeof(name), "%u triangles, split 4", n);
        mesh_soup(&m, n);
        check_split(gpu, name, &m, 4.0f, 1000);
        mesh_free(&m);
    }
    for (uint32_t n = 0; n <= 3; n++) {
        char name[32];
        snprintf(name, sizeof(name), "%u triangle(s)", n);
        mesh_soup(&m, n);
        check_mesh(gpu, name, &m, 1000, false);
        mesh_free(&m);
    }
    check_deep(gpu);
    check_corrupt(gpu);
    check_large(gpu);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
