/* media.c: MakeNamedMedium, MediumInterface and the camera's medium, as
 * pbrt-v4 reads them. Media go to the scene's table (glsl/shared/medium.h:
 * number 0 is vacuum); a shape's MediumInterface goes into its material's
 * media word, so a material used with several interfaces is copied once
 * per interface. Grid media (nanovdb too) are read by media_grid.c, the
 * cloud by media_cloud.c; a homogeneous medium's "preset" names one of the
 * measured media of scattering_presets.c. */
#include <math.h>
#include <string.h>

#include "base/mem.h"
#include "scene/builder.h"
#include "scene/scattering_presets.h"

/* pbrt-v4's HomogeneousMedium defaults. */
#define DEFAULT_SIGMA 1.0

/* Adds m, made by the statement at loc, with its source (scene.h:
 * medium_sources) and the end of its floats in the grid buffer. */
static uint32_t add_medium(struct cv_builder *b, const CvMedium *m, const char *name,
                           const struct cv_loc *loc)
{
    struct cv_scene *s = b->s;
    size_t n = s->n_media;
    if (n == 0) {
        CvMedium vacuum;
        memset(&vacuum, 0, sizeof(vacuum));
        CV_PUSH(s->media, n, b->cap_media, vacuum);
    }
    CV_PUSH(s->media, n, b->cap_media, *m);
    s->medium_sources = cv_xrealloc(s->medium_sources, n * sizeof(*s->medium_sources));
    if (n == 2)
        s->medium_sources[0] = (struct cv_medium_source){NULL, 0};
    s->medium_sources[n - 1] = (struct cv_medium_source){
        cv_xasprintf("%s:%d:%d: medium \"%s\"", loc->file, loc->line, loc->col, name),
        s->n_medium_grids};
    s->n_media = (uint32_t)n;
    return (uint32_t)(n - 1);
}

static bool sigma(struct cv_builder *b, struct cv_params *ps, const char *name,
                  const char *dir, double out[3], struct cv_error *err)
{
    bool found;
    out[0] = out[1] = out[2] = DEFAULT_SIGMA;
    return cv_b_color(b, ps, name, CV_SPEC_UNBOUNDED, dir, out, &found, err);
}

bool cv_b_medium_g(struct cv_builder *b, struct cv_params *ps, const char *name,
                   const struct cv_loc *loc, double *g, struct cv_error *err)
{
    *g = cv_params_float(ps, "g", 0);
    if (*g > -1 && *g < 1)
        return true;
    if (!cv_b_warn(b, err, loc, "medium \"%s\": g %g is outside (-1, 1); clamped", name, *g))
        return false;
    *g = *g <= -1 ? -0.999 : 0.999;
    return true;
}

/* A homogeneous medium's "string preset": pbrt-v4's named measured media
 * (scattering_presets.c), which take the place of sigma_a and sigma_s
 * (pbrt-v4 then leaves those unread: unused parameters); "scale" applies
 * to them as to explicit ones. An unknown name is an error at the
 * parameter (pbrt-v4 warns and falls back to sigma_a and sigma_s). */
static bool medium_preset(struct cv_params *ps, const char *name, double sa[3], double ss[3],
                          bool *found, struct cv_error *err)
{
    *found = false;
    const char *preset = cv_params_string(ps, "preset", NULL);
    if (!preset || !*preset)
        return true;
    if (!cv_scattering_preset(preset, sa, ss)) {
        struct cv_param *p = cv_params_find(ps, "preset");
        return cv_fail(err, "%s:%d:%d: medium \"%s\": unknown preset \"%s\" (the names are "
                            "pbrt-v4's measured media, e.g. \"Wholemilk\", \"Skin1\", "
                            "\"Ketchup\")", p->file, p->line, p->col, name, preset);
    }
    *found = true;
    return true;
}

bool cv_b_medium(struct cv_builder *b, const char *name, struct cv_params *ps,
                 const struct cv_loc *loc, const char *dir, struct cv_error *err)
{
    const char *type = cv_params_string(ps, "type", NULL);
    if (!type)
        return cv_fail(err, "%s:%d:%d: MakeNamedMedium \"%s\" has no \"string type\"", loc->file,
                       loc->line, loc->col, name);
    if (cv_b_lookup(b->media_named, b->n_media_named, name) >= 0 &&
        !cv_b_warn(b, err, loc, "named medium \"%s\" redefined", name))
        return false;
    CvMedium m;
    memset(&m, 0, sizeof(m));
    if (strcmp(type, "homogeneous") == 0) {
        double sa[3], ss[3], Le[3] = {0, 0, 0};
        bool found, preset;
        if (!medium_preset(ps, name, sa, ss, &preset, err))
            return false;
        if (!preset &&
            (!sigma(b, ps, "sigma_a", dir, sa, err) || !sigma(b, ps, "sigma_s", dir, ss, err)))
            return false;
        if (!cv_b_color(b, ps, "Le", CV_SPEC_ILLUMINANT, dir, Le, &found, err))
            return false;
        double scale = cv_params_float(ps, "scale", 1);
        double le_scale = cv_params_float(ps, "Lescale", 1);
        double g;
        if (!cv_b_medium_g(b, ps, name, loc, &g, err))
            return false;
        for (int c = 0; c < 3; c++) {
            if (!(sa[c] * scale >= 0) || !(ss[c] * scale >= 0) || !isfinite(sa[c] * scale) ||
                !isfinite(ss[c] * scale))
                return cv_fail(err, "%s:%d:%d: medium \"%s\": sigma_a and sigma_s must be "
                                    "finite and not negative", loc->file, loc->line, loc->col,
                               name);
        }
        m.type = CV_MEDIUM_HOMOGENEOUS;
        m.sigma_a = (cv_vec4){(float)(sa[0] * scale), (float)(sa[1] * scale),
                              (float)(sa[2] * scale), (float)g};
        m.sigma_s = (cv_vec4){(float)(ss[0] * scale), (float)(ss[1] * scale),
                              (float)(ss[2] * scale), 0};
        m.Le = (cv_vec4){(float)(Le[0] * le_scale), (float)(Le[1] * le_scale),
                         (float)(Le[2] * le_scale), 0};
        m.emissive = m.Le.x > 0 || m.Le.y > 0 || m.Le.z > 0;
    } else if (strcmp(type, "uniformgrid") == 0 || strcmp(type, "rgbgrid") == 0 ||
               strcmp(type, "nanovdb") == 0) {
        if (!cv_b_medium_grid(b, name, type, ps, loc, dir, &m, err))
            return false;
    } else if (strcmp(type, "cloud") == 0) {
        if (!cv_b_medium_cloud(b, name, ps, loc, dir, &m, err))
            return false;
    } else {
        for (size_t i = 0; i < ps->n; i++)
            ps->v[i].used = true;
        if (!cv_b_warn(b, err, loc,
                       "medium \"%s\": type \"%s\" is not rendered (homogeneous, uniformgrid, "
                       "rgbgrid, nanovdb and cloud are); it is vacuum", name, type))
            return false;
        m.type = CV_MEDIUM_VACUUM;
    }
    if (b->s->n_media >= CV_MAX_MEDIA + 1)
        return cv_fail(err, "%s:%d:%d: medium \"%s\": more than %u media", loc->file, loc->line,
                       loc->col, name, CV_MAX_MEDIA);
    uint32_t idx = add_medium(b, &m, name, loc);
    cv_b_set_named(&b->media_named, &b->n_media_named, &b->cap_media_named, name, (int)idx);
    return true;
}

/* The number of medium `name` ("" is vacuum); an unknown name warns (an
 * error with --strict) and stands for vacuum. */
static bool medium_number(struct cv_builder *b, const char *name, const struct cv_loc *loc,
                          int *out, struct cv_error *err)
{
    *out = 0;
    if (name[0] == '\0')
        return true;
    int i = cv_b_lookup(b->media_named, b->n_media_named, name);
    if (i < 0)
        return cv_b_warn(b, err, loc, "unknown medium \"%s\"; vacuum used", name);
    *out = i;
    return true;
}

bool cv_b_medium_interface(struct cv_builder *b, const char *inside, const char *outside,
                           const struct cv_loc *loc, struct cv_error *err)
{
    return medium_number(b, inside, loc, &b->gs.medium_inside, err) &&
           medium_number(b, outside, loc, &b->gs.medium_outside, err);
}

uint32_t cv_b_material_in_media(struct cv_builder *b, uint32_t material)
{
    if (b->gs.medium_inside == b->gs.medium_outside)
        return material;
    uint32_t word = CV_MEDIA_WORD((uint32_t)b->gs.medium_inside, (uint32_t)b->gs.medium_outside);
    struct cv_scene *s = b->s;
    for (size_t i = 0; i < b->n_media_copies; i++)
        if (b->media_copies[i].base == material && b->media_copies[i].word == word)
            return b->media_copies[i].copy;
    CvMaterial m = s->materials[material];
    m.media = word;
    const char *name = s->material_names[material];
    struct cv_media_copy c = {material, word, cv_b_add_material(b, &m, name)};
    CV_PUSH(b->media_copies, b->n_media_copies, b->cap_media_copies, c);
    return c.copy;
}
