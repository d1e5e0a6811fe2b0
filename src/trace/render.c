/* render.c: see render.h. The stages follow pbrt-v4's wavefront
 * integrator: generate camera rays; per iteration: reset the queues,
 * intersect (closest), escaped rays, surface hits (emission, NEE, BSDF
 * sampling: the integrator's shade programs, then its own work, as its
 * entry in trace/integrator.h says), shadow rays; a path that ends starts its slot's next sample in the stage
 * that ends it (path regeneration, glsl/shared/trace.h); the film
 * accumulates in place. Queue counts stay on the GPU: the last work group
 * of the intersect and shade stages turns them into the next stages'
 * indirect dispatch arguments (glsl/trace/queue_args.glsl). The host reads
 * one count back per CV_CHUNK iterations, a chunk behind the GPU, only to
 * learn when the pass is over. */
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/limits.h"
#include "base/log.h"
#include "base/mem.h"
#include "glsl/shared/bssrdf.h"
#include "glsl/shared/trace.h"
#include "gpu/buf.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/memory.h"
#include "gpu/program.h"
#include "gpu/storage.h"
#include "gpu/timer.h"
#include "trace/camera_motion.h"
#include "trace/filter_table.h"
#include "trace/guide_choice.h"
#include "trace/integrator.h"
#include "trace/render.h"
#include "trace/rlpath.h"
#include "trace/scene_defines.h"
#include "trace/scene_upload.h"

/* Iterations queued between looks at whether the pass is over. Small, so
 * that a pass ends soon after its last path (every queued iteration after
 * that is a few empty dispatches); large enough that the look, a chunk
 * behind, never leaves the GPU idle. */
#define CV_CHUNK 4

enum stage {
    ST_GENERATE,
    ST_INTERSECT,
    ST_ESCAPED,
    ST_SHADE,
    ST_SHADE_B,
    ST_SHADE_C,
    ST_SHADOW,
    ST_RESOLVE,
    ST_MATTE,             /* only for alpha and ID AOVs (matte.comp) */
    ST_RESOLVE_STRAIGHT,  /* only for alpha: un-premultiplied, for the colour stage */
    ST_COUNT
};

/* The stage timer's row beyond the stages: the integrator's work after the
 * shade stage (cv_integrator_ops.after_shade). */
enum { PROF_AFTER_SHADE = ST_COUNT, PROF_COUNT };

/* The stage timer's slots: the iterations of a pass by index, up to this
 * many, each with the rays its intersect stage traced: the traversal rate
 * against the wave's size. */
#define PROF_ITERS 64

struct cv_renderer {
    struct cv_gpu *gpu;
    const struct cv_scene_gpu *scene;  /* borrowed, or owned_scene */
    struct cv_scene_gpu *owned_scene;  /* cv_renderer_create's own upload */
    /* copies: the cache's entries move as it grows (ids stay valid) */
    struct cv_program prog[ST_COUNT];
    uint32_t n_pixels, crop_w, crop_h;
    uint32_t paths_per_pixel;      /* K of glsl/shared/trace.h */
    size_t n_paths;                /* path slots: n_pixels * paths_per_pixel */
    uint32_t wave_paths;           /* whole samples: slots a dispatch runs (choose_wave_paths) */
    uint32_t max_depth;
    bool aovs;
    /* this pass's misses start their slots' next samples in the escaped
     * stage (escaped.comp, built with escaped_defines), else in the
     * intersect stage (set_misses) */
    bool escaped_stage;
    const char *const *escaped_defines;
    enum cv_misses misses;         /* params', then choose_misses' choice */
    bool alpha;                    /* film transparency (render.h) */
    uint32_t matte_stride;         /* uints a slot in `matte` (glsl/shared/trace.h); 0: none */
    uint32_t spp_done;
    uint64_t iterations;           /* over all passes, for the counters */
    uint64_t n_passes;             /* passes run (cv_renderer_pass may split one) */
    CvPassParams pass;
    GLuint ubo, queues, rays, hits, shadow, film;
    GLuint matte;                  /* coverage and ID mattes, with matte_stride */
    GLuint medium_paths;           /* volpath's channel ratios per path slot (0: no media) */
    bool media;                    /* the stages track media (CV_MEDIA) */
    /* subsurface materials: each path slot's entry (point, normal,
     * coefficients) while its BSSRDF probe is traced (glsl/trace/sss_vertex.glsl), as a buffer
     * and its rgba32f buffer texture; 0 without subsurface */
    GLuint sss_entry, sss_entry_tex;
    struct cv_buf *resolved;       /* RGBA float a pixel, handed to the colour stage */
    GLuint alive[2];               /* rays-out count at the end of a chunk, by chunk parity */
    GLuint queues_copy;            /* cv_renderer_counters' read-back staging */
    struct cv_gpu_timer *passes;   /* one row: every pass, start to end */
    const struct cv_integrator_ops *ops;
    void *integrator;              /* ops->create's state, or NULL */
    bool learning;                 /* this pass learns (ops->learn_spp); after_shade runs */
    /* the stage programs (requested at creation): the first pass's, and
     * those that later passes get (set_misses, use_programs_after_learning) */
    struct stage_programs *sp;
    bool freezes;                  /* passes after learning get frozen programs (freezes()) */
    bool frozen;                   /* prog holds the programs after learning */
    /* a guided integrator's choice after learning (choice_passes), until
     * made; then whether path's programs render on */
    struct cv_guide_choice *choice;
    bool choice_sub;               /* a pass of the choice's runs */
    /* ... and its figures once made (cv_render_counters) */
    bool choice_measured;
    double choice_err[2], choice_ms[2], choice_z;
    bool unguided;
    bool prog_unguided;            /* prog holds path's programs after learning */
    bool misses_later;             /* later passes may choose their misses' way (request_all) */
    /* params' stage_times: GPU time of every dispatch by stage, and by the
     * pass's iteration (a diagnostic: the scopes cost time themselves);
     * NULL: off */
    struct cv_gpu_timer *stages;
    const char *stage_rows[PROF_COUNT];  /* its row names: the stages, then ops' */
    size_t made_bytes;             /* the storage make() created, for the set-up's log line */
    struct {
        GLuint counts;             /* rays in of the pass's iterations 0..PROF_ITERS-1 */
        uint64_t iter_rays[PROF_ITERS];
        uint32_t iter;             /* the iteration of the scopes marked now (its slot) */
    } prof;
};

static const char *const stage_names[ST_COUNT] = {
    "generate", "intersect", "escaped", "shade",  "shade-b", "shade-c",
    "shadow",   "resolve",   "matte",   "resolve-straight",
};

static const char *const pass_names[1] = {"pass"};

/* Opens and closes a scope of the stage timer (nothing when it is off). */
static void prof_begin(struct cv_renderer *r, int stage)
{
    cv_gpu_timer_begin(r->stages, (unsigned)stage, r->prof.iter);
}

static void prof_end(struct cv_renderer *r)
{
    cv_gpu_timer_end(r->stages);
}

/* The shade stages' files come from the integrator (NULL here). */
static const char *const stage_files[ST_COUNT] = {
    "trace/generate.comp", "trace/intersect.comp", "trace/escaped.comp", NULL,
    NULL,                  NULL,                   "trace/shadow.comp",  "trace/resolve.comp",
    "trace/matte.comp",    "trace/resolve.comp",
};

/* The film and camera: the plan's (p->camera), else the scene's. */
static void setup_camera(struct cv_renderer *r, const struct cv_scene *s,
                         const struct cv_render_params *p)
{
    const CvCamera *c = p->camera ? p->camera : &s->camera;
    uint32_t cw = c->crop.x, ch = c->crop.y;
    r->crop_w = cw;
    r->crop_h = ch;
    r->n_pixels = cw * ch;
    CvPassParams *u = &r->pass;
    u->n_pixels = r->n_pixels;
    u->crop_w = cw;
    u->crop_h = ch;
    u->film = c->film;
    for (int i = 0; i < 3; i++)
        u->cam_to_world[i] = c->to_world[i];
    u->screen = c->screen;
    u->lens_radius = c->lens.x;
    u->focal_distance = c->lens.y;
    u->tan_half_fov = c->lens.z;
    u->camera_type = c->type;
    cv_camera_motion_setup(c, u);
}

/* A storage buffer of the renderer, zeroed or (zero false) of undefined
 * contents. */
static GLuint make_buffer(struct cv_renderer *r, size_t bytes, bool zero, const char *label,
                          bool *ok, struct cv_error *err)
{
    if (!*ok)
        return 0;
    GLuint b = zero ? cv_gpu_storage_buffer(r->gpu, bytes, NULL, label, err)
                    : cv_gpu_storage_buffer_uninit(r->gpu, bytes, label, err);
    if (!b)
        *ok = false;
    r->made_bytes += bytes;
    return b;
}

static GLuint make(struct cv_renderer *r, size_t bytes, const char *label, bool *ok,
                   struct cv_error *err)
{
    return make_buffer(r, bytes, true, label, ok, err);
}

/* For a queue's items, which a stage reads only below the count that the
 * stage before wrote them up to: no zero-fill, which for fresh storage
 * costs time in proportion to its size (gpu/buffer.h). */
static GLuint make_queue(struct cv_renderer *r, size_t bytes, const char *label, bool *ok,
                         struct cv_error *err)
{
    return make_buffer(r, bytes, false, label, ok, err);
}

/* params' stage_times: the set-up's steps (the time before a job's first
 * pass that is not the scene's), each waited for (glFinish) so that the
 * GPU work a step queues counts in it. A diagnostic: the waits cost time. */
enum setup_step { SETUP_PROGRAMS, SETUP_INTEGRATOR, SETUP_BUFFERS, SETUP_STEPS };

struct setup_clock {
    bool on;
    double at;                  /* [s] the last step's end */
    double ms[SETUP_STEPS];
};

static void setup_start(struct setup_clock *c, bool on)
{
    *c = (struct setup_clock){.on = on};
    if (on) {
        glFinish();
        c->at = cv_seconds();
    }
}

static void setup_step(struct setup_clock *c, enum setup_step s)
{
    if (!c->on)
        return;
    glFinish();
    double now = cv_seconds();
    c->ms[s] += 1e3 * (now - c->at);
    c->at = now;
}

static void setup_report(const struct setup_clock *c, const struct cv_renderer *r)
{
    if (!c->on)
        return;
    cv_info("renderer set-up (each step waited for): programs %.1f ms, integrator state %.1f ms, "
            "path buffers %.1f ms (%zu MB), %zu path slots (%u a pixel)",
            c->ms[SETUP_PROGRAMS], c->ms[SETUP_INTEGRATOR], c->ms[SETUP_BUFFERS],
            r->made_bytes >> 20, r->n_paths, r->paths_per_pixel);
}

/* Bytes a path slot takes: its rays (two halves), hits (two), shadow ray
 * and film entry. */
#define PATH_BYTES (2 * sizeof(CvRayItem) + 2 * sizeof(CvHitItem) + sizeof(CvShadowItem) + \
                    sizeof(CvFilmPixel))

/* How many path slots an integrator's own storage (cv_integrator_ops.
 * slot_bytes: bdpt's subpath vertices) holds at most: in one storage
 * buffer (the driver's per-buffer limit, GL_MAX_SHADER_STORAGE_BLOCK_SIZE
 * or what a probe found: gpu/storage.h), and within a quarter of the free
 * memory where the driver reports it. UINT64_MAX: no storage of its own,
 * or no bound known. */
static uint64_t own_slots(struct cv_gpu *gpu, const struct cv_integrator_ops *ops,
                          uint32_t max_depth)
{
    uint64_t own = ops->slot_bytes ? ops->slot_bytes(max_depth) : 0, cap = UINT64_MAX;
    if (!own)
        return cap;
    uint64_t known = cv_gpu_storage_known(gpu);
    if (known && known / own < cap)
        cap = known / own;
    uint64_t total = 0, avail = 0;
    if (cv_gpu_memory(gpu, &total, &avail) && avail && avail / 4 / own < cap)
        cap = avail / 4 / own;
    return cap;
}

/* The path slots one dispatch of a whole-sample integrator runs (render.h:
 * bdpt_slots): all n_paths where its own storage holds them, else waves of
 * as many as it holds, ops->max_paths at most (enough to fill the GPU; the
 * store stays bounded for any film). Waves change where a sample's
 * subpaths are kept, nothing else: each slot still runs the same samples,
 * in the same order. */
static uint32_t choose_wave_paths(struct cv_gpu *gpu, const struct cv_render_params *p,
                                  const struct cv_integrator_ops *ops, uint32_t max_depth,
                                  uint64_t n_paths)
{
    uint64_t cap = own_slots(gpu, ops, max_depth);
    if (ops->max_paths && ops->max_paths < cap)
        cap = ops->max_paths;
    if (p->bdpt_slots && p->bdpt_slots < cap)
        cap = p->bdpt_slots;
    if (n_paths < cap)
        cap = n_paths;
    return cap < 1 ? 1 : (uint32_t)cap;
}

/* Path slots per pixel (render.h: paths_per_pixel). The automatic choice
 * is made for the full film (film_pixels), not for the pixels a crop
 * renders: K sets the order in which a pixel's samples are summed, so a
 * tile must use the K of the whole image to give its pixels bit for bit. */
static bool choose_paths_per_pixel(struct cv_gpu *gpu, const struct cv_render_params *p,
                                   uint32_t n_pixels, uint64_t film_pixels, uint32_t max_depth,
                                   uint32_t *out, struct cv_error *err)
{
    uint64_t max_paths = CV_MAX_PATHS;
    if (p->paths_per_pixel) {
        if ((uint64_t)n_pixels * p->paths_per_pixel > max_paths)
            return cv_fail(err, "%u paths per pixel over %u pixels: more than 2^24 paths",
                           p->paths_per_pixel, n_pixels);
        *out = p->paths_per_pixel;
        return true;
    }
    /* Only for speed, so never into a probed storage size, nor into memory
     * that scenes or other jobs might want. */
    uint64_t cap = CV_WAVE_PATHS < max_paths ? CV_WAVE_PATHS : max_paths;
    const struct cv_integrator_ops *ops = cv_integrator_for(p);
    if (ops->max_paths && ops->max_paths < cap)
        cap = ops->max_paths;
    uint64_t known = cv_gpu_storage_known(gpu);
    /* an integrator's own storage per slot (bdpt's subpath vertices):
     * where the whole film's slots fit it, one dispatch a round runs them
     * all (choose_wave_paths) */
    uint64_t own = own_slots(gpu, ops, max_depth);
    if (own < cap)
        cap = own;
    if (known && known / (2 * sizeof(CvRayItem)) < cap)
        cap = known / (2 * sizeof(CvRayItem));
    uint64_t total = 0, avail = 0;
    if (cv_gpu_memory(gpu, &total, &avail) && avail / 8 / PATH_BYTES < cap)
        cap = avail / 8 / PATH_BYTES;
    if (cap < 1)
        cap = 1;
    uint32_t k = CV_MAX_PATHS_PER_PIXEL;
    while (k > 1 && film_pixels * k > cap)
        k--;
    *out = k;
    return true;
}

static bool check_params(const struct cv_scene *scene, const struct cv_render_params *p,
                         struct cv_error *err)
{
    if (!cv_integrator_for(p))
        return cv_fail(err, "unknown integrator %d", (int)p->integrator);
    if (p->sampler != CV_SAMPLER_SOBOL && p->sampler != CV_SAMPLER_INDEPENDENT)
        return cv_fail(err, "unknown sampler %d", (int)p->sampler);
    const CvCamera *c = p->camera ? p->camera : &scene->camera;
    if (c->film.x == 0 || c->film.y == 0 || c->crop.x == 0 || c->crop.y == 0)
        return cv_fail(err, "scene has no film resolution");
    return true;
}

bool cv_renderer_create(struct cv_gpu *gpu, const struct cv_scene *scene,
                        const struct cv_render_params *p, struct cv_renderer **out,
                        struct cv_error *err)
{
    /* bad parameters fail before the upload and BVH build */
    if (!check_params(scene, p, err))
        return false;
    cv_renderer_prefetch(gpu, scene, p);
    struct cv_scene_gpu *gs = NULL;
    if (!cv_scene_gpu_create(gpu, scene, p->bvh, &gs, err)) {
        cv_error_prefix(err, "uploading the scene: ");
        return false;
    }
    if (!cv_renderer_create_shared(gpu, gs, scene, p, out, err)) {
        cv_scene_gpu_destroy(&gs);
        return false;
    }
    (*out)->owned_scene = gs;
    return true;
}

/* out = the nd defines plus `a` and `b` where not NULL, NULL-terminated;
 * out has room for nd + 3 entries and may be defines itself (appending).
 * Returns out's count, for a further append. */
static int defines_plus(const char **out, const char *const *defines, int nd, const char *a,
                        const char *b)
{
    memmove(out, defines, (size_t)nd * sizeof(*out));
    if (a)
        out[nd++] = a;
    if (b)
        out[nd++] = b;
    out[nd] = NULL;
    return nd;
}

/* The stage programs a render of gs with p runs: file and defines by stage
 * (file NULL: the stage has none, or the integrator's create makes it).
 * One home for the choice, for cv_renderer_create_shared and for
 * cv_renderer_prefetch. */
struct stage_programs {
    /* each list: the scene's defines (trace/scene_defines.h), then a
     * stage's own (defines_plus) and the NULL */
    const char *scene_defines[CV_SCENE_DEFINES_MAX + 1];
    const char *file[ST_COUNT];
    const char *const *defines[ST_COUNT];
    /* the escaped stage's: while the integrator learns (with its
     * escaped_define), and otherwise (plain) */
    const char *escaped[CV_SCENE_DEFINES_MAX + 3];
    const char *escaped_plain[CV_SCENE_DEFINES_MAX + 2];
    /* the intersect stage's: misses to the escaped queue, and misses that
     * start their slots' next samples in the stage (regen) */
    const char *intersect[CV_SCENE_DEFINES_MAX + 3];
    const char *intersect_regen[CV_SCENE_DEFINES_MAX + 2];
    bool has_env;                  /* the scene's misses need the escaped stage */
    /* (a shade bin's: its integrator's define, CV_NO_COAT_CLOSED,
     * CV_NO_TEXTURES, CV_BSDF_WALK_ONLY and CV_RL_UNGUIDED where they
     * apply) */
    const char *shade[CV_SHADE_PROGRAMS][CV_SCENE_DEFINES_MAX + 6];
    char stride[32];  /* CV_MATTE_STRIDE=N */
    const char *matte[CV_SCENE_DEFINES_MAX + 3];
    const char *resolve[CV_SCENE_DEFINES_MAX + 4];
    const char *straight[CV_SCENE_DEFINES_MAX + 5];
    /* a whole-sample integrator's program (ops->create, ops->prefetch):
     * the scene's defines, and the matte stage's and escaped stage's
     * where the job asks for mattes (it runs neither stage) */
    const char *integrator[CV_SCENE_DEFINES_MAX + 4];
    const char *const *integrator_defines;
    const char *shadow[CV_SCENE_DEFINES_MAX + 3];
    /* the passes that do not learn (integrator.h: frozen_programs), by
     * stage (NULL: the stage's own program): the shade programs' defines
     * plus CV_FROZEN, the shadow stage's without the integrator's (their
     * misses: set_misses) */
    const char *const *frozen[ST_COUNT];
    const char *shade_frozen[CV_SHADE_PROGRAMS][CV_SCENE_DEFINES_MAX + 7];
    /* a guided integrator's passes after learning that the choice runs
     * unguided (chooses()), by stage (NULL: the stage's program after
     * learning): path's shade programs (unguided_file) with path's
     * defines, and the shadow stage's without the integrator's */
    const char *unguided_file[ST_COUNT];
    const char *const *unguided[ST_COUNT];
    const char *shade_path[CV_SHADE_PROGRAMS][CV_SCENE_DEFINES_MAX + 6];
};

static const char *const misses_names[] = {"auto", "intersect", "stage"};
_Static_assert(CV_ARRAY_SIZE(misses_names) == CV_MISSES_COUNT, "one name per enum cv_misses");
const struct cv_names cv_misses_names = {misses_names, CV_MISSES_COUNT};

/* What a pass runs for its misses: through the escaped stage, with these
 * defines, or not (the intersect stage starts their slots' next samples,
 * intersect.comp); and the intersect stage's defines for it. The stage is
 * needed while the integrator learns from misses (ops->escaped_stage) and
 * for an environment light; elsewhere both render the same image, and m
 * says which (CV_MISSES_AUTO, undecided: path's way, in the intersect
 * stage). */
struct pass_misses {
    bool stage;
    const char *const *escaped;
    const char *const *intersect;
};

static struct pass_misses pass_misses(const struct stage_programs *sp, bool learns,
                                      enum cv_misses m)
{
    if (learns)
        return (struct pass_misses){true, sp->escaped, sp->intersect};
    bool stage = sp->has_env || m == CV_MISSES_STAGE;
    return (struct pass_misses){stage, sp->escaped_plain,
                                stage ? sp->intersect : sp->intersect_regen};
}

/* The samples per pixel a job with p learns for (0: none, or every
 * pass). */
static uint32_t train_spp(const struct cv_integrator_ops *ops, const struct cv_render_params *p)
{
    return ops->train_spp ? ops->train_spp(p) : 0;
}

/* Whether a job with p may have passes that do not learn after some that
 * do, whose programs differ (frozen_programs, pass_misses). */
static bool passes_after_learning(const struct cv_integrator_ops *ops,
                                  const struct cv_render_params *p)
{
    uint32_t train = train_spp(ops, p);
    return train != 0 && (p->spp == 0 || p->spp > train);
}

/* Words per path slot of the matte stage (trace.h), 0 when the job asks
 * for neither alpha nor ID mattes. */
static uint32_t matte_words(const struct cv_render_params *p)
{
    if (!p->alpha && !p->id_mattes && !p->cryptomatte)
        return 0;
    return p->cryptomatte ? CV_MATTE_WORDS_CRYPTO : CV_MATTE_WORDS;
}

/* Whether a job with params p has passes that do not learn, which run
 * programs without the learning code (integrator.h: frozen_programs). */
static bool freezes(const struct cv_integrator_ops *ops, const struct cv_render_params *p)
{
    return ops->frozen_programs && passes_after_learning(ops, p);
}

/* Whether a job with p measures, after learning, whether its guide pays
 * for its cost (trace/guide_choice.h): a guided integrator's, with passes
 * after learning, not told which. */
static bool chooses(const struct cv_integrator_ops *ops, const struct cv_render_params *p)
{
    return ops->guides && p->rl_choice != CV_RL_CHOICE_GUIDED && passes_after_learning(ops, p);
}

/* ... and makes the choice by measuring (trace/guide_choice.h), not told
 * to go on unguided. */
static bool measures_choice(const struct cv_integrator_ops *ops, const struct cv_render_params *p)
{
    return chooses(ops, p) && p->rl_choice == CV_RL_CHOICE_MEASURE;
}

static void stage_programs(const struct cv_scene_gpu *gs, const struct cv_render_params *p,
                           struct stage_programs *sp)
{
    static const char *const no_defines[1] = {NULL};
    memset(sp, 0, sizeof(*sp));
    const char **defines = sp->scene_defines;
    int nd = 0;
    const struct cv_integrator_ops *ops = cv_integrator_for(p);
#define ADD_SCENE_DEFINE(name, when) \
    if (when)                        \
        defines[nd++] = (name);
    CV_SCENE_DEFINES(ADD_SCENE_DEFINE)
#undef ADD_SCENE_DEFINE
    defines[nd] = NULL;
    const char *transparent = p->alpha ? "CV_FILM_TRANSPARENT" : NULL;
    defines_plus(sp->escaped, defines, nd, ops->escaped_define, transparent);
    /* the passes that do not learn: without the integrator's code */
    defines_plus(sp->escaped_plain, defines, nd, transparent, NULL);
    sp->has_env = gs->has_env;
    /* (the whole-sample integrators run neither stage) */
    struct pass_misses first = pass_misses(sp, ops->escaped_stage, p->misses);
    /* the matte stages: the slot layout, and what the job asked for */
    uint32_t words = matte_words(p);
    snprintf(sp->stride, sizeof(sp->stride), "CV_MATTE_STRIDE=%uu", words);
    defines_plus(sp->matte, defines, nd, sp->stride, p->cryptomatte ? "CV_CRYPTO" : NULL);
    int nr = defines_plus(sp->resolve, defines, nd, transparent, p->alpha ? sp->stride : NULL);
    nr = defines_plus(sp->resolve, sp->resolve, nr, ops->resolve_define, NULL);
    defines_plus(sp->straight, sp->resolve, nr, "CV_RESOLVE_STRAIGHT", NULL);
    sp->integrator_defines = defines;
    if (ops->whole_samples && words) {
        int ni = defines_plus(sp->integrator, defines, nd, sp->stride,
                              p->cryptomatte ? "CV_CRYPTO" : NULL);
        defines_plus(sp->integrator, sp->integrator, ni, transparent, NULL);
        sp->integrator_defines = sp->integrator;
    }
    defines_plus(sp->shadow, defines, nd, ops->shadow_define, NULL);
    /* hits binned by material for the shade stages (intersect.comp) */
    defines_plus(sp->intersect, defines, nd, "CV_HIT_BINS", "CV_ESCAPED_QUEUE");
    defines_plus(sp->intersect_regen, defines, nd, "CV_HIT_BINS", NULL);
    /* shade bins (trace/shade_bins.h): bin 0's program always (its groups
     * prepare the shadow stage: shade_queue.glsl), the others' only where
     * the scene's materials use them (volpath's medium events and
     * subsurface probes are bin 1's);
     * the coated walk's without the closed-form coat where none of its
     * materials may take it; a bin's without the texture code where none
     * of its materials reads a texture, the walk's without the other
     * materials' code where none of its materials is a mix, and a guided
     * integrator's without the guide where it serves none of the bin's
     * materials (trace/shade_bins.h) */
    uint32_t bins_used = 1u | gs->shade_bins | (ops->media && gs->has_media ? 2u : 0u) |
                         (gs->has_subsurface ? 2u : 0u);
    /* the guide's choice runs path's shade programs, whose bins and their
     * defines are the guided integrators' (trace/integrator.c): a bin's
     * are its guided program's but CV_RL_UNGUIDED */
    const struct cv_integrator_ops *path = cv_integrator_find(CV_INTEGRATOR_PATH);
    for (int k = 0; k < ops->n_shade; k++) {
        const char *coat = ops->bins[k] == 4u && gs->has_coat_closed && !gs->walk_coat_closed
                               ? "CV_NO_COAT_CLOSED"
                               : NULL;
        bool no_tex = gs->has_textures && ops->bins[k] && !(ops->bins[k] & gs->textured_bins);
        const char *walk_only = ops->bins[k] == 4u && gs->walk_only ? "CV_BSDF_WALK_ONLY" : NULL;
        int ns = defines_plus(sp->shade[k], defines, nd, ops->define[k], coat);
        ns = defines_plus(sp->shade[k], sp->shade[k], ns, no_tex ? "CV_NO_TEXTURES" : NULL,
                          walk_only);
        if (ops->guides)
            defines_plus(sp->shade_path[k], sp->shade[k], ns, NULL, NULL);
        bool unguided = ops->guides && ops->bins[k] && !(ops->bins[k] & gs->guided_bins);
        ns = defines_plus(sp->shade[k], sp->shade[k], ns, unguided ? "CV_RL_UNGUIDED" : NULL,
                          NULL);
        defines_plus(sp->shade_frozen[k], sp->shade[k], ns, "CV_FROZEN", NULL);
    }
    for (int s = 0; s < ST_COUNT; s++) {
        const char *file = stage_files[s];
        const char *const *d = defines;
        if (s >= ST_SHADE && s < ST_SHADE + CV_SHADE_PROGRAMS) {
            int k = s - ST_SHADE;
            if (k >= ops->n_shade || !ops->file[k] || (ops->bins[k] && !(ops->bins[k] & bins_used)))
                continue;
            file = ops->file[k];
            d = sp->shade[k];
        }
        if ((s == ST_ESCAPED && !first.stage) || (s == ST_MATTE && !words) ||
            (s == ST_RESOLVE_STRAIGHT && !p->alpha))
            continue;
        /* a whole-sample integrator runs its program and the resolve alone */
        if (ops->whole_samples && s != ST_SHADE && s != ST_RESOLVE && s != ST_RESOLVE_STRAIGHT)
            continue;
        if (s == ST_GENERATE)
            d = no_defines;
        else if (s == ST_ESCAPED)
            d = first.escaped;
        else if (s == ST_INTERSECT)
            d = first.intersect;
        else if (s == ST_MATTE)
            d = sp->matte;
        else if (s == ST_RESOLVE)
            d = sp->resolve;
        else if (s == ST_RESOLVE_STRAIGHT)
            d = sp->straight;
        else if (s == ST_SHADOW)
            d = sp->shadow;
        sp->file[s] = file;
        sp->defines[s] = d;
        bool shade = s >= ST_SHADE && s < ST_SHADE + CV_SHADE_PROGRAMS;
        if (chooses(ops, p) && (shade || s == ST_SHADOW)) {
            sp->unguided_file[s] = shade ? path->file[s - ST_SHADE] : file;
            sp->unguided[s] = shade ? sp->shade_path[s - ST_SHADE] : defines;
        }
        if (!freezes(ops, p))
            continue;
        if (shade)
            sp->frozen[s] = sp->shade_frozen[s - ST_SHADE];
        else if (s == ST_SHADOW)
            sp->frozen[s] = defines;
    }
}

/* Whether the passes after the first (after learning, for an integrator
 * that learns from misses) of a job with p may choose their misses' way
 * (set_misses); else every pass runs the first one's. */
static bool misses_later(const struct cv_integrator_ops *ops, const struct cv_render_params *p)
{
    if (ops->whole_samples)
        return false;
    return ops->escaped_stage ? passes_after_learning(ops, p) : p->spp != 1;
}

/* Requests the stages' programs and the integrator's own, then those of
 * the passes after learning (integrator.h: frozen_programs): the driver
 * builds them beside the others, so that the first pass that does not
 * learn, which waits for them, seldom waits on a cold cache. (It waits
 * rather than run on with the learning programs, so which program renders
 * a pass never depends on the driver's speed, nor do its bits.) */
static void request_all(struct cv_gpu *gpu, const struct cv_render_params *p,
                        const struct stage_programs *sp)
{
    for (int s = 0; s < ST_COUNT; s++)
        if (sp->file[s])
            cv_program_request(gpu, sp->file[s], sp->defines[s]);
    const struct cv_integrator_ops *ops = cv_integrator_for(p);
    if (ops->prefetch)
        ops->prefetch(gpu, p, sp->integrator_defines);
    for (int s = 0; s < ST_COUNT; s++)
        if (sp->file[s] && sp->frozen[s])
            cv_program_request(gpu, sp->file[s], sp->frozen[s]);
    /* the guide's choice's: path's, shared with path's jobs, and the
     * measure's own */
    for (int s = 0; s < ST_COUNT; s++)
        if (sp->unguided[s])
            cv_program_request(gpu, sp->unguided_file[s], sp->unguided[s]);
    if (measures_choice(ops, p))
        cv_guide_choice_request(gpu);
    /* the misses' programs of the passes after the first (after learning,
     * for an integrator that learns from misses) that may run the other
     * way (pass_misses; a program already requested is not built twice) */
    if (!misses_later(ops, p))
        return;
    for (int m = CV_MISSES_INTERSECT; m <= CV_MISSES_STAGE; m++) {
        if (p->misses != CV_MISSES_AUTO && p->misses != (enum cv_misses)m)
            continue;
        struct pass_misses pm = pass_misses(sp, false, (enum cv_misses)m);
        cv_program_request(gpu, stage_files[ST_INTERSECT], pm.intersect);
        if (pm.stage)
            cv_program_request(gpu, stage_files[ST_ESCAPED], pm.escaped);
    }
}

void cv_renderer_prefetch(struct cv_gpu *gpu, const struct cv_scene *scene,
                          const struct cv_render_params *p)
{
    struct cv_scene_gpu features = {0};
    cv_scene_gpu_features(scene, &features);
    struct stage_programs sp;
    stage_programs(&features, p, &sp);
    request_all(gpu, p, &sp);
}

bool cv_renderer_create_shared(struct cv_gpu *gpu, const struct cv_scene_gpu *gs,
                               const struct cv_scene *scene, const struct cv_render_params *p,
                               struct cv_renderer **out, struct cv_error *err)
{
    if (!check_params(scene, p, err))
        return false;
    /* the ID mattes read each triangle's object from a buffer texture */
    if ((p->id_mattes || p->cryptomatte) && scene->n_triangles && !gs->tri_object_tex)
        return cv_fail(err, "ID mattes of %u triangles: more than this GPU's buffer textures "
                            "hold", scene->n_triangles);

    struct setup_clock clock;
    setup_start(&clock, p->stage_times);
    struct cv_renderer *r = cv_xcalloc(1, sizeof(*r));
    r->gpu = gpu;
    r->aovs = p->aovs;
    r->alpha = p->alpha;
    r->matte_stride = matte_words(p);
    r->max_depth = p->max_depth ? p->max_depth : scene->settings.max_depth;
    setup_camera(r, scene, p);
    cv_filter_setup(&scene->settings, &r->pass);
    if ((uint64_t)r->crop_w * r->crop_h > CV_MAX_FILM_PIXELS) {
        uint32_t w = r->crop_w, h = r->crop_h;
        free(r);
        return cv_fail(err, "film of %ux%u pixels is too large", w, h);
    }
    const CvCamera *cam = p->camera ? p->camera : &scene->camera;
    uint64_t film_pixels = (uint64_t)cam->film.x * cam->film.y;
    if (!choose_paths_per_pixel(gpu, p, r->n_pixels, film_pixels, r->max_depth,
                                &r->paths_per_pixel, err)) {
        free(r);
        return false;
    }
    r->n_paths = (size_t)r->n_pixels * r->paths_per_pixel;
    r->pass.n_paths = (uint32_t)r->n_paths;
    r->wave_paths = (uint32_t)r->n_paths;
    r->pass.paths_per_pixel = r->paths_per_pixel;
    r->pass.seed_lo = (uint32_t)p->seed;
    r->pass.seed_hi = (uint32_t)(p->seed >> 32);
    r->pass.sampler = p->sampler == CV_SAMPLER_INDEPENDENT ? 1u : 0u;
    r->pass.max_depth = r->max_depth;
    r->pass.iteration = 0;
    /* lights to sample at each vertex; 0 turns next-event estimation off,
     * and with it the MIS weights of emission hits */
    r->pass.n_lights = p->no_nee ? 0 : scene->n_lights;
    r->pass.end_sample = 0;
    r->passes = cv_gpu_timer_create(gpu, &(struct cv_gpu_timer_params){
                                             .names = pass_names, .n_names = 1});
    if (p->stage_times) {
        const struct cv_integrator_ops *sops = cv_integrator_for(p);
        for (int k = 0; k < ST_COUNT; k++)
            r->stage_rows[k] = stage_names[k];
        r->stage_rows[PROF_AFTER_SHADE] =
            sops->after_shade_name ? sops->after_shade_name : "after-shade";
        r->stages = cv_gpu_timer_create(gpu, &(struct cv_gpu_timer_params){
                                                 .names = r->stage_rows, .n_names = PROF_COUNT,
                                                 .n_slots = PROF_ITERS});
    }

    r->scene = gs;

    const struct cv_integrator_ops *ops = cv_integrator_for(p);
    r->ops = ops;
    if (ops->whole_samples) {
        r->wave_paths = choose_wave_paths(gpu, p, ops, r->max_depth, r->n_paths);
        cv_debug("%s: %zu path slots, %u a dispatch (%zu dispatches a round of samples)",
                 cv_integrator_name(p->integrator), r->n_paths, r->wave_paths,
                 (r->n_paths + r->wave_paths - 1) / r->wave_paths);
    }
    /* media are tracked by an integrator that renders them, in a scene
     * that has them; camera rays start in the camera's medium */
    if (ops->media && r->scene->has_media) {
        r->media = true;
        r->pass.camera_medium = scene->camera_medium;
    }
    /* on the heap: later passes get their programs from it (set_misses,
     * use_programs_after_learning) */
    struct stage_programs *sp = cv_xcalloc(1, sizeof(*sp));
    r->sp = sp;
    stage_programs(gs, p, sp);
    r->misses = p->misses;
    r->misses_later = misses_later(ops, p);
    r->freezes = freezes(ops, p);
    r->escaped_stage = sp->file[ST_ESCAPED] != NULL;
    r->escaped_defines = sp->defines[ST_ESCAPED];
    /* all requested before the first is waited for: the driver compiles
     * them side by side (gpu/program.h) */
    request_all(gpu, p, sp);
    for (int s = 0; s < ST_COUNT; s++) {
        if (!sp->file[s])
            continue;
        struct cv_program *pr = cv_program_get(gpu, sp->file[s], sp->defines[s], err);
        if (pr)
            r->prog[s] = *pr;
        if (!pr) {
            cv_renderer_destroy(&r);
            return false;
        }
    }
    const char *const *defines = sp->integrator_defines;
    setup_step(&clock, SETUP_PROGRAMS);
    /* the guide's choice after learning: measured, or told */
    r->unguided = chooses(ops, p) && p->rl_choice == CV_RL_CHOICE_UNGUIDED;
    if (measures_choice(ops, p) &&
        !cv_guide_choice_create(gpu, r->n_pixels, 0, &r->choice, err)) {
        cv_renderer_destroy(&r);
        return false;
    }

    if (ops->create) {
        struct cv_integrator_setup setup = {
            .gpu = gpu,
            .scene = scene,
            .params = p,
            .defines = defines,
            .n_paths = (uint32_t)r->n_paths,
            .wave_paths = r->wave_paths,
            .n_pixels = r->n_pixels,
            .max_depth = r->max_depth,
        };
        struct cv_program made[CV_SHADE_PROGRAMS];
        if (!ops->create(&setup, &r->integrator, made, err)) {
            cv_renderer_destroy(&r);
            return false;
        }
        for (int k = 0; k < ops->n_shade; k++)
            if (!ops->file[k])
                r->prog[ST_SHADE + k] = made[k];
    }
    setup_step(&clock, SETUP_INTEGRATOR);

    size_t n = r->n_paths;
    bool ok = true;
    r->ubo = make(r, sizeof(CvPassParams), "trace pass params", &ok, err);
    r->queues = make(r, sizeof(CvTraceQueues), "trace queues", &ok, err);
    /* a whole-sample integrator's program declares no queues (CV_NO_QUEUES) */
    if (!ops->whole_samples) {
        r->rays = make_queue(r, 2 * n * sizeof(CvRayItem), "trace rays", &ok, err);
        r->hits = make_queue(r, 2 * n * sizeof(CvHitItem), "trace hits and escaped rays", &ok,
                             err);
        r->shadow = make_queue(r, n * sizeof(CvShadowItem), "trace shadow rays", &ok, err);
    }
    r->film = make(r, n * sizeof(CvFilmPixel), "trace film", &ok, err);
    if (r->matte_stride)
        r->matte = make(r, n * r->matte_stride * sizeof(uint32_t), "trace mattes", &ok, err);
    /* a whole-sample integrator (bdpt) keeps its ratios in registers */
    /* starts cleared (make zeroes it): no slot's ratios belong to a path
     * yet (track.glsl) */
    if (r->media && !ops->whole_samples)
        r->medium_paths = make(r, n * 4 * sizeof(float), "trace medium paths", &ok, err);
    if (r->scene->has_subsurface && ok) {
        size_t texels = n * CV_SSS_ENTRY_TEXELS;
        r->sss_entry = make(r, texels * 4 * sizeof(float), "trace subsurface entries", &ok, err);
        if (ok && !(r->sss_entry_tex = cv_buffer_texture(r->sss_entry, GL_RGBA32F, texels, err)))
            ok = false;
    }
    if (ok && !(r->resolved = cv_buf_create(gpu, &(struct cv_buf_params){
                                                      .size = (size_t)r->n_pixels * 4 * sizeof(float),
                                                      .storable = true, .host_readable = true,
                                                      .label = "trace resolved"},
                                           err)))
        ok = false;
    r->made_bytes += (size_t)r->n_pixels * 4 * sizeof(float);
    if (r->stages)
        r->prof.counts = make(r, PROF_ITERS * sizeof(uint32_t), "trace stage-time ray counts",
                              &ok, err);
    r->alive[0] = make(r, sizeof(uint32_t), "trace pass end check 0", &ok, err);
    r->alive[1] = make(r, sizeof(uint32_t), "trace pass end check 1", &ok, err);
    r->queues_copy = make(r, sizeof(CvTraceQueues), "trace queues read-back", &ok, err);
    if (!ok) {
        cv_error_prefix(err, "allocating the film and queues for %ux%u, %u paths a pixel: ",
                        r->crop_w, r->crop_h, r->paths_per_pixel);
        cv_renderer_destroy(&r);
        return false;
    }
    setup_step(&clock, SETUP_BUFFERS);
    setup_report(&clock, r);
    *out = r;
    return true;
}

static void bind_all(struct cv_renderer *r)
{
    cv_scene_bind(r->scene);
    glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_PASS, r->ubo);
    cv_buffer_bind(r->queues, CV_BIND_QUEUES);
    cv_buffer_bind(r->rays, CV_BIND_RAYS);
    cv_buffer_bind(r->hits, CV_BIND_HITS);
    cv_buffer_bind(r->shadow, CV_BIND_SHADOW);
    cv_buffer_bind(r->film, CV_BIND_FILM);
    if (r->matte)
        cv_buffer_bind(r->matte, CV_BIND_MATTE);
    if (r->medium_paths)
        cv_buffer_bind(r->medium_paths, CV_BIND_MEDIUM_PATHS);
    if (r->sss_entry_tex)
        glBindImageTexture(CV_IMAGE_SSS_ENTRY, r->sss_entry_tex, 0, GL_FALSE, 0, GL_READ_WRITE,
                           GL_RGBA32F);
    cv_buf_bind(r->resolved, CV_BIND_RESOLVED);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, r->queues);
    if (r->ops->bind)
        r->ops->bind(r->integrator);
}

static void stage_indirect(struct cv_renderer *r, int s, uint32_t slot)
{
    prof_begin(r, s);
    bool images = r->ops->image_stages && r->learning;
    cv_program_dispatch_indirect(&r->prog[s], CV_ARGS_BYTES(slot),
                                 images ? GL_SHADER_IMAGE_ACCESS_BARRIER_BIT : 0);
    prof_end(r);
}

/* One iteration: a bounce of every path in flight; the slots whose paths
 * end start their next samples on the way. */
static void iterate(struct cv_renderer *r, uint32_t it)
{
    r->pass.iteration = it;
    glNamedBufferSubData(r->ubo, (GLintptr)offsetof(CvPassParams, iteration),
                         sizeof(r->pass.iteration), &r->pass.iteration);
    if (r->stages && it < PROF_ITERS) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glCopyNamedBufferSubData(r->queues, r->prof.counts,
                                 (GLintptr)(sizeof(uint32_t) * CV_Q_RAYS_IN),
                                 (GLintptr)(sizeof(uint32_t) * it), sizeof(uint32_t));
    }
    r->prof.iter = it < PROF_ITERS ? it : PROF_ITERS;  /* no slot: its rays are not counted */
    stage_indirect(r, ST_INTERSECT, CV_ARGS_RAYS);
    if (r->escaped_stage)
        stage_indirect(r, ST_ESCAPED, CV_ARGS_ESCAPED);
    /* reads the hits before the shade stages move on from them */
    if (r->matte)
        stage_indirect(r, ST_MATTE, CV_ARGS_HITS_ALL);
    /* The shade programs share no data (integrator.h), so only the last
     * is followed by a barrier and they may overlap. A program the scene
     * does not need was not built (stage_programs). */
    const struct cv_integrator_ops *ops = r->ops;
    int last = ops->n_shade - 1;
    while (last > 0 && !r->prog[ST_SHADE + last].id)
        last--;
    for (int k = 0; k < last; k++) {
        if (!r->prog[ST_SHADE + k].id)
            continue;
        prof_begin(r, ST_SHADE + k);
        glUseProgram(r->prog[ST_SHADE + k].id);
        glDispatchComputeIndirect(CV_ARGS_BYTES(ops->args[k]));
        prof_end(r);
    }
    stage_indirect(r, ST_SHADE + last, ops->args[last]);
    /* the probes' entries, stored by this shade stage, for the next one's */
    if (r->sss_entry_tex)
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    if (ops->after_shade && r->learning) {
        prof_begin(r, PROF_AFTER_SHADE);
        ops->after_shade(r->integrator);
        prof_end(r);
    }
    stage_indirect(r, ST_SHADOW, CV_ARGS_SHADOW);
}

/* A pass of a whole-sample integrator (integrator.h): round k runs every
 * slot's k-th sample of the pass, in dispatches over waves of at most
 * wave_paths slots (one wave where the integrator's own storage holds
 * every slot: choose_wave_paths). A round of n slots costs ceil(n /
 * wave_paths) dispatches, each followed by a storage barrier, as the next
 * wave reuses the store: a few per round for films whose store would pass
 * the per-buffer limit, no extra work per sample. */
static bool whole_samples_pass(struct cv_renderer *r, uint32_t spp, struct cv_error *err)
{
    uint32_t slots = r->paths_per_pixel, rounds = (spp + slots - 1) / slots;
    const struct cv_program *prog = &r->prog[ST_SHADE];
    cv_program_set_uint(prog, "u_wave_paths", r->wave_paths);
    for (uint32_t k = 0; k < rounds; k++) {
        r->pass.iteration = k;
        glNamedBufferSubData(r->ubo, (GLintptr)offsetof(CvPassParams, iteration),
                             sizeof(r->pass.iteration), &r->pass.iteration);
        prof_begin(r, ST_SHADE);
        for (size_t first = 0; first < r->n_paths; first += r->wave_paths) {
            size_t n = r->n_paths - first < r->wave_paths ? r->n_paths - first : r->wave_paths;
            cv_program_set_uint(prog, "u_wave_first", (uint32_t)first);
            /* with a storage barrier: the next wave reuses the store */
            cv_program_dispatch_1d(prog, n);
        }
        prof_end(r);
        /* the next round reads the film and vertex store; resolve reads both films */
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
    }
    cv_gpu_timer_end(r->passes);
    if (!cv_gl_check(err, "rendering a pass of %u spp", spp))
        return false;
    r->iterations += rounds;
    r->n_passes++;
    r->spp_done += spp;
    return true;
}

/* choose_misses: misses start their slots' next samples in an escaped
 * stage where fewer than this share of the rays traced so far left the
 * scene, else in the intersect stage (bench/RESULTS.md, "Misses by
 * scene") */
#define CV_MISSES_STAGE_BELOW 0.05

/* The queues' counters and statistics. Staged, or the queues' atomics and
 * indirect arguments would live in host memory from the first pass on,
 * which slows every stage (gpu/buffer.h; bench/RESULTS.md, "Renderer
 * counters through a copy"). Waits for the GPU. */
static bool read_queues(struct cv_renderer *r, CvTraceQueues *q, struct cv_error *err)
{
    return cv_buffer_read_staged(r->queues, 0, sizeof(*q), r->queues_copy, q, err);
}

static uint64_t stat64(const CvTraceQueues *q, uint32_t slot)
{
    return (uint64_t)q->stats[slot].y << 32 | q->stats[slot].x;
}

/* CV_MISSES_AUTO's choice, by the rays of the passes so far. Reads back
 * from the GPU: once per job. */
static bool choose_misses(struct cv_renderer *r, struct cv_error *err)
{
    CvTraceQueues q;
    if (!read_queues(r, &q, err))
        return false;
    uint64_t rays = stat64(&q, CV_STAT_EXTEND), hits = stat64(&q, CV_STAT_HITS);
    double missed = rays ? (double)(rays - hits) / rays : 0;
    r->misses = missed < CV_MISSES_STAGE_BELOW ? CV_MISSES_STAGE : CV_MISSES_INTERSECT;
    cv_debug("misses: %.4f of %" PRIu64 " rays left the scene: started in the %s stage", missed,
             rays, r->misses == CV_MISSES_STAGE ? "escaped" : "intersect");
    return true;
}

/* A pass's misses' programs (pass_misses), past the first pass (and past
 * learning where the integrator learns from misses), choosing where not
 * told. Waits for the driver where a cold cache still builds them. */
static bool set_misses(struct cv_renderer *r, struct cv_error *err)
{
    bool learns = r->ops->escaped_stage && r->learning;
    if (learns || r->spp_done == 0)
        return true;   /* the first pass's */
    if (r->misses == CV_MISSES_AUTO && !r->sp->has_env && !choose_misses(r, err))
        return false;
    struct pass_misses pm = pass_misses(r->sp, false, r->misses);
    if (pm.stage == r->escaped_stage && (!pm.stage || pm.escaped == r->escaped_defines))
        return true;
    struct cv_program *pi = cv_program_get(r->gpu, stage_files[ST_INTERSECT], pm.intersect, err);
    struct cv_program *pe =
        pi && pm.stage ? cv_program_get(r->gpu, stage_files[ST_ESCAPED], pm.escaped, err) : NULL;
    if (!pi || (pm.stage && !pe))
        return false;
    r->prog[ST_INTERSECT] = *pi;
    if (pe)
        r->prog[ST_ESCAPED] = *pe;
    r->escaped_stage = pm.stage;
    r->escaped_defines = pm.escaped;
    return true;
}

/* From the first pass that does not learn on: the programs built without
 * the learning code (sp->frozen), or path's (sp->unguided) where
 * `unguided`. Waits for the driver where a cold cache still builds them. */
static bool use_programs_after_learning(struct cv_renderer *r, bool unguided,
                                        struct cv_error *err)
{
    const struct stage_programs *sp = r->sp;
    if (r->frozen && r->prog_unguided == unguided)
        return true;
    int n = 0;
    for (int s = 0; s < ST_COUNT; s++) {
        if (!sp->file[s] || (!sp->frozen[s] && !sp->unguided[s]))
            continue;
        const char *file = sp->file[s];
        const char *const *d = sp->frozen[s] ? sp->frozen[s] : sp->defines[s];
        if (unguided && sp->unguided[s]) {
            file = sp->unguided_file[s];
            d = sp->unguided[s];
        }
        struct cv_program *pr = cv_program_get(r->gpu, file, d, err);
        if (!pr)
            return false;
        n += r->prog[s].id != pr->id;
        r->prog[s] = *pr;
    }
    r->frozen = true;
    r->prog_unguided = unguided;
    /* (Q-learning's guided programs are its learning ones: none changes) */
    if (n)
        cv_debug("passes after learning: %d stage programs %s", n,
                 unguided ? "of path's" : "of the guide's, without the learning code");
    return true;
}

/* After learning, the guide's choice (trace/guide_choice.h): its
 * sub-passes, of two rounds of the path slots each where spp allows,
 * then the rest of spp with the programs it chose. A pass may hold only
 * some of the sub-passes; the next goes on with them. */
static bool choice_passes(struct cv_renderer *r, uint32_t spp, struct cv_error *err)
{
    uint32_t sub = 2 * r->paths_per_pixel;
    r->choice_sub = true;
    bool ok = true;
    while (ok && spp > 0 && cv_guide_choice_pending(r->choice)) {
        uint32_t n = spp < sub ? spp : sub;
        ok = use_programs_after_learning(r, cv_guide_choice_next_unguided(r->choice), err);
        bind_all(r);
        ok = ok && cv_guide_choice_begin(r->choice, err) && cv_renderer_pass(r, n, err);
        bind_all(r);
        ok = ok && cv_guide_choice_end(r->choice, n, r->spp_done, err);
        spp -= n;
    }
    r->choice_sub = false;
    if (!ok || cv_guide_choice_pending(r->choice))
        return ok;
    r->unguided = cv_guide_choice_unguided(r->choice);
    cv_guide_choice_measures(r->choice, r->choice_err, r->choice_ms, &r->choice_z);
    r->choice_measured = true;
    cv_guide_choice_destroy(&r->choice);
    return use_programs_after_learning(r, r->unguided, err) && cv_renderer_pass(r, spp, err);
}

bool cv_renderer_pass(struct cv_renderer *r, uint32_t spp, struct cv_error *err)
{
    if (spp == 0)
        return true;
    if ((uint64_t)r->spp_done + spp > CV_MAX_SPP)
        return cv_fail(err, "more than %u samples per pixel", CV_MAX_SPP);
    /* a learning integrator's last learning pass ends where it stops */
    uint32_t until = r->ops->learn_spp ? r->ops->learn_spp(r->integrator) : 0;
    if (until > r->spp_done && r->spp_done + spp > until) {
        uint32_t first = until - r->spp_done;
        return cv_renderer_pass(r, first, err) && cv_renderer_pass(r, spp - first, err);
    }
    r->learning = until == 0 || r->spp_done < until;
    /* a learning pass of more samples than slots a pixel, where the
     * integrator asks for it, as passes of one path a slot */
    uint32_t ppp = r->paths_per_pixel;
    if (r->learning && r->ops->learn_path_a_slot && spp > ppp) {
        for (uint32_t done = 0; done < spp; done += ppp)
            if (!cv_renderer_pass(r, spp - done < ppp ? spp - done : ppp, err))
                return false;
        return true;
    }
    if (!r->learning && r->choice && !r->choice_sub)
        return choice_passes(r, spp, err);
    if (!r->learning && (r->freezes || r->unguided) && !r->frozen &&
        !use_programs_after_learning(r, r->unguided, err))
        return false;
    if (r->misses_later && !set_misses(r, err))
        return false;
    /* (an integrator that sets frozen_programs never learns again) */
    if (r->learning && r->frozen)
        return cv_fail(err, "the integrator learns again after its passes without learning");
    if (r->ops->set_learning)
        r->ops->set_learning(r->integrator, r->learning);
    cv_gpu_timer_begin(r->passes, 0, 0);
    bind_all(r);
    /* the slots that have a sample in this pass (generate.comp) */
    uint32_t slots = r->paths_per_pixel, started = spp < slots ? spp : slots;
    r->pass.first_sample = r->spp_done;
    r->pass.iteration = 0;
    r->pass.end_sample = r->spp_done + spp;
    r->pass.camera_rays = r->n_pixels * started;
    glNamedBufferSubData(r->ubo, 0, sizeof(CvPassParams), &r->pass);
    if (r->ops->whole_samples)
        return whole_samples_pass(r, spp, err);
    prof_begin(r, ST_GENERATE);
    cv_program_dispatch_1d(&r->prog[ST_GENERATE], r->pass.camera_rays);
    prof_end(r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    /* Every path ends within max_depth + 1 iterations (twice that with
     * subsurface probes, an iteration each on top of its bounce) and a
     * slot runs at most ceil(spp / slots) of them, so this bounds the pass
     * even if a count were never read back as 0. */
    uint64_t per_path = (uint64_t)(r->max_depth + 1) * (r->sss_entry ? 2 : 1);
    uint64_t limit = (uint64_t)((spp + slots - 1) / slots) * per_path + CV_CHUNK;
    uint64_t it = 0;
    uint32_t alive = 1;
    for (uint32_t chunk = 0; it < limit; chunk++) {
        for (int k = 0; k < CV_CHUNK && it < limit; k++, it++)
            iterate(r, (uint32_t)it);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        /* the rays the next iteration would trace (queue_args.glsl) */
        glCopyNamedBufferSubData(r->queues, r->alive[chunk & 1],
                                 (GLintptr)(sizeof(uint32_t) * CV_Q_RAYS_IN), 0,
                                 sizeof(uint32_t));
        /* the previous chunk's count: waits for that chunk while this one runs */
        if (chunk > 0) {
            if (!cv_buffer_read(r->alive[(chunk - 1) & 1], 0, sizeof(alive), &alive, err))
                return false;
            if (alive == 0)
                break;
        }
    }
    cv_gpu_timer_end(r->passes);
    if (r->stages) {
        /* a diagnostic: this read-back waits for the pass */
        uint32_t counts[PROF_ITERS], n = it < PROF_ITERS ? (uint32_t)it : PROF_ITERS;
        if (!cv_buffer_read(r->prof.counts, 0, n * sizeof(uint32_t), counts, err))
            return false;
        for (uint32_t i = 0; i < n; i++)
            r->prof.iter_rays[i] += counts[i];
    }
    if (!cv_gl_check(err, "rendering a pass of %u spp", spp))
        return false;
    r->iterations += it;
    r->n_passes++;
    r->spp_done += spp;
    if (r->learning && r->ops->pass_done && !r->ops->pass_done(r->integrator, r->spp_done, err))
        return false;
    return true;
}

uint32_t cv_renderer_spp_done(const struct cv_renderer *r)
{
    return r->spp_done;
}

void cv_renderer_size(const struct cv_renderer *r, uint32_t *width, uint32_t *height)
{
    *width = r->crop_w;
    *height = r->crop_h;
}

bool cv_renderer_counters(struct cv_renderer *r, struct cv_render_counters *c,
                          struct cv_error *err)
{
    cv_gpu_timer_collect(r->passes);
    cv_gpu_timer_collect(r->stages);
    CvTraceQueues q;
    if (!read_queues(r, &q, err))
        return false;
    uint64_t extend = stat64(&q, CV_STAT_EXTEND);
    c->primary_rays = (uint64_t)r->n_pixels * r->spp_done;
    c->path_slots = r->n_paths;
    c->wave_slots = r->wave_paths;
    c->secondary_rays = extend > c->primary_rays ? extend - c->primary_rays : 0;
    c->iterations = r->iterations;
    c->passes = r->n_passes;
    c->shadow_rays = stat64(&q, CV_STAT_SHADOW);
    c->nonfinite_samples = q.stats[CV_STAT_NONFINITE].x;
    c->missed_rays = extend - stat64(&q, CV_STAT_HITS);
    c->escaped_stage = r->escaped_stage;
    c->unguided = r->unguided && r->frozen;
    c->choice_measured = r->choice_measured;
    for (int k = 0; k < 2; k++)
        c->choice_err[k] = r->choice_err[k], c->choice_ms[k] = r->choice_ms[k];
    c->choice_z = r->choice_z;
    c->gpu_ms = cv_gpu_timer_ms(r->passes, 0);
    /* all 0 when the stage timer is off */
    c->intersect_first_ms = cv_gpu_timer_slot_ms(r->stages, ST_INTERSECT, 0);
    c->intersect_ms = cv_gpu_timer_ms(r->stages, ST_INTERSECT);
    c->shadow_ms = cv_gpu_timer_ms(r->stages, ST_SHADOW);
    c->first_bounce_ms = cv_gpu_timer_slot_ms(r->stages, ST_INTERSECT, 1);
    c->first_bounce_rays = r->stages ? r->prof.iter_rays[1] : 0;
    return cv_gl_check(err, "reading render counters");
}

static const struct cv_buf *resolve(struct cv_renderer *r, int stage, struct cv_error *err)
{
    glNamedBufferSubData(r->ubo, 0, sizeof(CvPassParams), &r->pass);
    bind_all(r);
    cv_program_dispatch_1d(&r->prog[stage], r->n_pixels);
    if (!cv_gl_check(err, "resolving the film"))
        return NULL;
    return r->resolved;
}

const struct cv_buf *cv_renderer_resolve(struct cv_renderer *r, struct cv_error *err)
{
    return resolve(r, ST_RESOLVE, err);
}

const struct cv_buf *cv_renderer_resolve_display(struct cv_renderer *r, struct cv_error *err)
{
    return resolve(r, r->alpha ? ST_RESOLVE_STRAIGHT : ST_RESOLVE, err);
}

bool cv_renderer_read(struct cv_renderer *r, float *rgba, float *albedo3, float *normal3,
                      float *depth1, struct cv_error *err)
{
    if ((albedo3 || normal3 || depth1) && !r->aovs)
        return cv_fail(err, "AOVs requested from a renderer made without them");
    size_t n = r->n_pixels, k = r->paths_per_pixel;
    if (rgba) {
        if (!cv_renderer_resolve(r, err))
            return false;
        if (!cv_buf_read(r->resolved, 0, n * 4 * sizeof(float), rgba, err))
            return false;
    }
    if (!albedo3 && !normal3 && !depth1)
        return true;
    CvFilmPixel *aov = cv_xmalloc(n * k * sizeof(CvFilmPixel));
    bool ok = cv_buffer_read(r->film, 0, n * k * sizeof(CvFilmPixel), aov, err);
    /* a pixel's sums are those of its slots, in slot order (resolve.comp) */
    for (size_t i = 0; ok && i < n; i++) {
        for (size_t s = 1; s < k; s++) {
            const CvFilmPixel *f = &aov[s * n + i];
            aov[i].L.w += f->L.w;
            aov[i].albedo.x += f->albedo.x;
            aov[i].albedo.y += f->albedo.y;
            aov[i].albedo.z += f->albedo.z;
            aov[i].albedo.w += f->albedo.w;
            aov[i].normal.x += f->normal.x;
            aov[i].normal.y += f->normal.y;
            aov[i].normal.z += f->normal.z;
        }
        float w = aov[i].L.w, inv = w != 0 ? 1 / w : 0;
        if (albedo3) {
            albedo3[3 * i + 0] = aov[i].albedo.x * inv;
            albedo3[3 * i + 1] = aov[i].albedo.y * inv;
            albedo3[3 * i + 2] = aov[i].albedo.z * inv;
        }
        if (normal3) {
            float x = aov[i].normal.x, y = aov[i].normal.y, z = aov[i].normal.z;
            float len = sqrtf(x * x + y * y + z * z), s = len > 0 ? 1 / len : 0;
            normal3[3 * i + 0] = x * s;
            normal3[3 * i + 1] = y * s;
            normal3[3 * i + 2] = z * s;
        }
        if (depth1)
            depth1[i] = aov[i].albedo.w * inv;
    }
    free(aov);
    return ok;
}

bool cv_renderer_read_matte_slots(struct cv_renderer *r, struct cv_matte_slots *out,
                                  struct cv_error *err)
{
    memset(out, 0, sizeof(*out));
    if (!r->matte)
        return cv_fail(err, "mattes requested from a renderer made without them");
    size_t n = r->n_paths;
    out->stride = r->matte_stride;
    out->slots_per_pixel = r->paths_per_pixel;
    out->n_pixels = r->n_pixels;
    out->words = cv_xmalloc(n * r->matte_stride * sizeof(uint32_t));
    out->weight = cv_xmalloc(n * sizeof(float));
    CvFilmPixel *film = cv_xmalloc(n * sizeof(CvFilmPixel));
    bool ok = cv_buffer_read(r->matte, 0, n * r->matte_stride * sizeof(uint32_t), out->words,
                             err) &&
              cv_buffer_read(r->film, 0, n * sizeof(CvFilmPixel), film, err);
    for (size_t i = 0; ok && i < n; i++)
        out->weight[i] = film[i].L.w;
    free(film);
    if (!ok)
        cv_matte_slots_free(out);
    return ok;
}

void cv_matte_slots_free(struct cv_matte_slots *m)
{
    free(m->words);
    free(m->weight);
    memset(m, 0, sizeof(*m));
}

void cv_renderer_destroy(struct cv_renderer **rp)
{
    if (!rp || !*rp)
        return;
    struct cv_renderer *r = *rp;
    if (r->stages) {
        cv_gpu_timer_report(r->stages, "stage");
        for (unsigned i = 0; i < PROF_ITERS; i++) {
            double ms = cv_gpu_timer_slot_ms(r->stages, ST_INTERSECT, i);
            if (r->prof.iter_rays[i] > 0 && ms > 0)
                cv_info("intersect iteration %2u %12" PRIu64 " rays %8.2f ms %6.3f G rays/s", i,
                        r->prof.iter_rays[i], ms, (double)r->prof.iter_rays[i] / (ms * 1e6));
        }
    }
    cv_gpu_timer_destroy(&r->stages);
    cv_gpu_timer_destroy(&r->passes);
    cv_guide_choice_destroy(&r->choice);
    GLuint *bufs[] = {&r->ubo,  &r->queues,   &r->rays,     &r->hits,    &r->shadow,
                      &r->film, &r->alive[0], &r->alive[1], &r->queues_copy, &r->prof.counts,
                      &r->matte, &r->medium_paths, &r->sss_entry};
    if (r->sss_entry_tex)
        glDeleteTextures(1, &r->sss_entry_tex);
    for (size_t i = 0; i < CV_ARRAY_SIZE(bufs); i++)
        cv_buffer_destroy(bufs[i]);
    cv_buf_destroy(&r->resolved);
    cv_scene_gpu_destroy(&r->owned_scene);
    free(r->sp);
    if (r->ops && r->ops->destroy)
        r->ops->destroy(&r->integrator);
    free(r);
    *rp = NULL;
}
