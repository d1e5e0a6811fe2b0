/* misses_test.c: where a miss starts its slot's next sample (render.h:
 * enum cv_misses) changes the time, never the image. In a closed room (no
 * ray leaves it) and a room open to the camera, path's image is the same
 * bit for bit with misses started in the intersect stage, in an escaped
 * stage, and as the renderer chooses from the first pass on; and so is
 * rlpath's at mix 0 (both methods; path's image, sample for sample) past
 * its training, whose passes learn from misses in the escaped stage
 * whatever is asked. Checked too: the counters' missed rays (none in the
 * closed room, more than the choice's threshold in the open one), the
 * automatic choice (the escaped stage in the closed room, the intersect
 * stage in the open one), and that an environment light keeps the escaped
 * stage even where the intersect stage is asked for. */
#include "config.h"

#include "tests/trace/rlpath_room.h"
#include "tests/trace/trace_test_util.h"

/* an environment light around the open room (escaped.comp adds it) */
static const char open_env[] =
    RLPATH_ROOM_VIEW "LightSource \"infinite\" \"rgb L\" [ 0.2 0.3 0.5 ]\n" RLPATH_ROOM_LIGHT
        RLPATH_ROOM_LAMP
    "Material \"diffuse\" \"rgb reflectance\" [ 0.7 0.7 0.7 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 4 6 5 4 7 6  0 3 7 0 7 4 ]\n"
    "  \"point3 P\" [ -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1 ]\n";

static size_t differ(const struct test_image *a, const struct test_image *b)
{
    size_t n = (size_t)a->w * a->h * 4, d = 0;
    for (size_t i = 0; i < n; i++)
        d += a->rgba[i] != b->rgba[i];
    return d;
}

/* Renders p with misses m over passes; false (and a failed check) on
 * error. */
static bool render(struct cv_gpu *gpu, const struct cv_scene *s, struct cv_render_params p,
                   enum cv_misses m, const uint32_t *passes, struct test_image *img,
                   const char *what)
{
    struct cv_error err = {{0}};
    p.misses = m;
    return tap_ok(test_render(gpu, s, &p, passes, img, &err), "%s, misses %s: renders: %s", what,
                  cv_name_of(&cv_misses_names, m), err.msg);
}

/* p's images with each way of misses: the same bits; the last pass ran
 * the escaped stage as asked, and as auto_stage says for the choice. */
static void same_image(struct cv_gpu *gpu, const struct cv_scene *s, struct cv_render_params p,
                       const uint32_t *passes, bool auto_stage, const char *what)
{
    struct test_image img[CV_MISSES_COUNT] = {{0}};
    bool ok = true;
    for (int m = 0; m < CV_MISSES_COUNT; m++)
        ok = ok && render(gpu, s, p, (enum cv_misses)m, passes, &img[m], what);
    if (ok) {
        size_t n = (size_t)img[0].w * img[0].h * 4;
        size_t di = differ(&img[CV_MISSES_AUTO], &img[CV_MISSES_INTERSECT]);
        size_t ds = differ(&img[CV_MISSES_AUTO], &img[CV_MISSES_STAGE]);
        tap_ok(di == 0 && ds == 0 && test_mean(&img[0], 0, NULL) > 0.01,
               "%s: the same image with misses started as chosen, in the intersect stage and "
               "in an escaped stage (%zu and %zu of %zu values differ; mean %.4f)", what, di, ds,
               n, test_mean(&img[0], 0, NULL));
        bool a = img[CV_MISSES_AUTO].counters.escaped_stage;
        bool i = img[CV_MISSES_INTERSECT].counters.escaped_stage;
        bool e = img[CV_MISSES_STAGE].counters.escaped_stage;
        tap_ok(a == auto_stage && !i && e,
               "%s: the last pass's escaped stage: chosen %d (want %d), intersect %d, stage %d",
               what, a, auto_stage, i, e);
    }
    for (int m = 0; m < CV_MISSES_COUNT; m++)
        free(img[m].rgba);
}

/* path's images, then rlpath's at mix 0 (equal to path's) trained over
 * the first pass */
static void room(struct cv_gpu *gpu, const char *text, size_t len, bool open, const char *name)
{
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {0};
    struct cv_scene *s = NULL;
    if (!tap_ok(cv_scene_load_string("room.pbrt", text, len, &lp, &s, &err), "%s: load: %s",
                name, err.msg))
        return;
    struct cv_render_params p = {.sampler = CV_SAMPLER_INDEPENDENT, .seed = 9, .spp = 9};
    const uint32_t passes[] = {1, 8, 0};
    char what[96];
    snprintf(what, sizeof(what), "%s, path", name);
    same_image(gpu, s, p, passes, !open, what);

    /* the share of rays that left: none, or past the automatic choice's
     * threshold by far (render.c: CV_MISSES_STAGE_BELOW) */
    struct test_image img = {0};
    if (render(gpu, s, p, CV_MISSES_AUTO, passes, &img, what)) {
        const struct cv_render_counters *c = &img.counters;
        double rays = (double)(c->primary_rays + c->secondary_rays);
        double share = c->missed_rays / rays;
        tap_ok(open ? share > 0.2 && share < 0.9 : c->missed_rays == 0,
               "%s: %.0f rays, %.4f of them missed", what, rays, share);
    }
    free(img.rgba);

    const uint32_t rl_passes[] = {4, 4, 0};
    for (int sd = 0; sd < 2; sd++) {
        struct cv_render_params r = p;
        r.integrator = CV_INTEGRATOR_RLPATH;
        r.rl_mix = 0;
        r.rl_sdtree = sd;
        r.rl_train = 4;
        r.spp = 8;
        snprintf(what, sizeof(what), "%s, rlpath %s mix 0", name, sd ? "sdtree" : "qlearn");
        same_image(gpu, s, r, rl_passes, !open, what);
    }
    cv_scene_destroy(&s);
}

/* an environment light needs the escaped stage in every pass */
static void environment(struct cv_gpu *gpu)
{
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {0};
    struct cv_scene *s = NULL;
    if (!tap_ok(cv_scene_load_string("env.pbrt", open_env, sizeof(open_env) - 1, &lp, &s, &err),
                "the open room with an environment light: load: %s", err.msg))
        return;
    struct cv_render_params p = {.sampler = CV_SAMPLER_INDEPENDENT, .seed = 9, .spp = 9};
    const uint32_t passes[] = {1, 8, 0};
    struct test_image a = {0}, b = {0};
    if (render(gpu, s, p, CV_MISSES_AUTO, passes, &a, "environment") &&
        render(gpu, s, p, CV_MISSES_INTERSECT, passes, &b, "environment")) {
        tap_ok(a.counters.escaped_stage && b.counters.escaped_stage && differ(&a, &b) == 0,
               "environment: the escaped stage whatever is asked (chosen %d, intersect %d), "
               "the same image (%zu values differ)",
               a.counters.escaped_stage, b.counters.escaped_stage, differ(&a, &b));
    }
    free(a.rgba), free(b.rgba);
    cv_scene_destroy(&s);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    room(gpu, rlpath_room, sizeof(rlpath_room) - 1, false, "closed room");
    room(gpu, rlpath_room_open, sizeof(rlpath_room_open) - 1, true, "open room");
    environment(gpu);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
