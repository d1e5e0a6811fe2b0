/* parse_test.c: every directive and parameter type of the pbrt importer,
 * what each becomes in the flat scene, and the errors (with file:line:col)
 * for broken input. */
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>

#include <OpenEXR/ImfCRgbaFile.h>
#include <png.h>

#include "base/mem.h"
#include "scene/filter.h"
#include "scene/image.h"
#include "scene/scene.h"
#include "tests/scene/scene_helpers.h"
#include "tests/tap.h"

#define TRI "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n"

static struct cv_scene *ok_load(const char *text, const char *desc)
{
    struct cv_error err = {0};
    struct cv_scene *s = th_load(text, false, &err);
    tap_ok(s != NULL, "%s loads%s%s", desc, s ? "" : ": ", s ? "" : err.msg);
    return s;
}

static void fails(const char *text, bool strict, const char *expect, const char *desc)
{
    struct cv_error err = {0};
    struct cv_scene *s = th_load(text, strict, &err);
    tap_ok(!s && strstr(err.msg, expect) != NULL, "%s fails with \"%s\": %s", desc, expect, err.msg);
    cv_scene_destroy(&s);
}

static bool near(double a, double b, double eps) { return fabs(a - b) <= eps; }

static bool vpos(const struct cv_scene *s, uint32_t v, double x, double y, double z)
{
    if (!s || v >= s->n_vertices)
        return false;
    const cv_vec4 *p = &s->vertices[v].pos_u;
    return near(p->x, x, 1e-5) && near(p->y, y, 1e-5) && near(p->z, z, 1e-5);
}

static const CvMaterial *tri_mat(const struct cv_scene *s, uint32_t t)
{
    return &s->materials[s->triangles[t].idx.w & CV_TRI_MATERIAL_MASK];
}

static void test_transforms(void)
{
    struct cv_scene *s;
    s = ok_load("WorldBegin\nTranslate 1 2 3\n" TRI, "Translate");
    tap_ok(vpos(s, 0, 1, 2, 3), "Translate moves vertices");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nScale 2 2 2 Rotate 90 0 0 1\n" TRI, "Scale+Rotate");
    tap_ok(vpos(s, 1, 0, 2, 0), "Rotate then Scale (pbrt order)");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nTransform [1 0 0 0 0 1 0 0 0 0 1 0 5 6 7 1]\n" TRI, "Transform");
    tap_ok(vpos(s, 0, 5, 6, 7), "Transform is column-major like pbrt");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nTranslate 1 0 0 ConcatTransform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1]\n" TRI,
                "ConcatTransform");
    tap_ok(vpos(s, 1, 3, 0, 0), "ConcatTransform post-multiplies");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nTranslate 1 0 0 Identity\n" TRI, "Identity");
    tap_ok(vpos(s, 0, 0, 0, 0), "Identity resets");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nTranslate 4 0 0 CoordinateSystem \"a\" Identity CoordSysTransform \"a\"\n" TRI,
                "CoordinateSystem");
    tap_ok(vpos(s, 0, 4, 0, 0), "CoordSysTransform restores a named system");
    cv_scene_destroy(&s);
    s = ok_load("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 60 ]\n"
                "Film \"rgb\" \"integer xresolution\" 200 \"integer yresolution\" 100\nWorldBegin\n",
                "LookAt + Camera");
    if (s) {
        const CvCamera *c = &s->camera;
        tap_ok(near(c->to_world[0].w, 0, 1e-6) && near(c->to_world[2].w, 5, 1e-6),
               "camera position from LookAt");
        tap_ok(near(c->to_world[2].z, -1, 1e-6), "camera looks down -z in world");
        tap_ok(near(c->lens.z, tan(M_PI / 6), 1e-6), "tan(fov/2)");
        tap_ok(near(c->screen.x, -2, 1e-6) && near(c->screen.w, 1, 1e-6), "screen window from aspect 2");
        tap_ok(c->film.x == 200 && c->film.y == 100 && c->crop.x == 200, "film size");
    }
    cv_scene_destroy(&s);
    s = ok_load("Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"orthographic\" \"float screenwindow\" [-2 2 -1 1]\n"
                "WorldBegin\nAttributeBegin\nCoordSysTransform \"camera\"\nLightSource \"distant\"\nAttributeEnd\n",
                "CoordSysTransform camera");
    if (s) {
        tap_ok(s->camera.type == CV_CAMERA_ORTHOGRAPHIC && near(s->camera.screen.x, -2, 1e-6),
               "orthographic with screenwindow");
        tap_ok(s->n_lights == 1 && near(s->lights[0].direction.z, -1, 1e-6),
               "distant light in camera space points along the view");
    }
    cv_scene_destroy(&s);
    /* pbrt-v4's spherical camera: equal area by default; its lens and
     * screen window read (no warning), fov not (a warning with --strict) */
    static const struct {
        const char *camera;
        uint32_t type;
    } sph[] = {
        {"\"spherical\" \"float lensradius\" 1 \"float screenwindow\" [0 1 0 1]", CV_CAMERA_EQUAL_AREA},
        {"\"spherical\" \"string mapping\" \"equalarea\"", CV_CAMERA_EQUAL_AREA},
        {"\"spherical\" \"string mapping\" \"equirectangular\"", CV_CAMERA_EQUIRECT},
        {"\"environment\"", CV_CAMERA_EQUIRECT},  /* pbrt-v3's */
    };
    for (size_t i = 0; i < sizeof(sph) / sizeof(sph[0]); i++) {
        char *text = cv_xasprintf("Camera %s\nWorldBegin\n", sph[i].camera);
        struct cv_error err = {0};
        s = th_load(text, true, &err);
        tap_ok(s && s->camera.type == sph[i].type && s->camera.lens.x == 0,
               "Camera %s: type %u, no lens (%s)", sph[i].camera, sph[i].type, s ? "" : err.msg);
        cv_scene_destroy(&s);
        free(text);
    }
    fails("Camera \"spherical\"\n  \"string mapping\" \"cube\"\nWorldBegin\n", false,
          ":2:3: unknown mapping \"cube\" of the spherical camera", "unknown spherical mapping");
    fails("Camera \"spherical\" \"float fov\" 30\nWorldBegin\n", true, "fov",
          "fov on a spherical camera is unused");
    s = ok_load("Camera \"perspective\" \"float lensradius\" 0.5\nCamera \"spherical\"\nWorldBegin\n",
                "a spherical camera after a thin lens");
    tap_ok(s && s->camera.lens.x == 0, "the spherical camera has no lens");
    cv_scene_destroy(&s);
}

static void test_attributes(void)
{
    struct cv_scene *s;
    s = ok_load("WorldBegin\nAttributeBegin\nTranslate 1 0 0\nAttributeEnd\n" TRI, "AttributeBegin/End");
    tap_ok(vpos(s, 0, 0, 0, 0), "AttributeEnd restores the transform");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nMaterial \"diffuse\"\nAttributeBegin\nMaterial \"conductor\"\n" TRI
                "AttributeEnd\n" TRI, "material in attributes");
    tap_ok(s && tri_mat(s, 0)->type == CV_MAT_CONDUCTOR && tri_mat(s, 1)->type == CV_MAT_DIFFUSE,
           "AttributeEnd restores the material");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nTransformBegin\nTranslate 1 0 0\nTransformEnd\n" TRI, "TransformBegin/End");
    tap_ok(vpos(s, 0, 0, 0, 0), "TransformEnd restores the transform");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nReverseOrientation\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]"
                " \"normal N\" [0 0 1 0 0 1 0 0 1]\n", "ReverseOrientation");
    tap_ok(s && (s->triangles[0].idx.w & CV_TRI_REVERSE) && (s->triangles[0].idx.w & CV_TRI_HAS_NORMAL) &&
           near(s->vertices[0].nrm_v.z, -1, 1e-6), "ReverseOrientation flags and flips normals");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nScale -1 1 1\n" TRI "ReverseOrientation\n" TRI, "handedness");
    tap_ok(s && (s->triangles[0].idx.w & CV_TRI_REVERSE) && !(s->triangles[1].idx.w & CV_TRI_REVERSE),
           "a handedness swap flags, and ReverseOrientation cancels it");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nObjectBegin \"o\"\n" TRI "ObjectEnd\nTranslate 5 0 0\nObjectInstance \"o\"\n"
                "Translate 5 0 0\nObjectInstance \"o\"\n", "ObjectBegin/Instance");
    tap_ok(s && s->n_triangles == 2 && vpos(s, 3, 10, 0, 0), "instances are flattened with their transform");
    cv_scene_destroy(&s);
    s = ok_load("Option \"bool disablepixeljitter\" true\nColorSpace \"srgb\"\nWorldBegin\n"
                "Attribute \"shape\" \"float radius\" [ 2 ]\n" TRI "WorldEnd\n", "Option, ColorSpace, Attribute, WorldEnd");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nMakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [1 2 3]\n"
                "  \"float scale\" [ 0.5 ] \"float g\" [ 0.25 ] \"rgb Le\" [ 1 1 1 ] \"float Lescale\" [ 2 ]\n"
                "MediumInterface \"fog\" \"\"\n" TRI "MediumInterface \"fog\"\n" TRI, "media parse");
    tap_ok(s && s->warnings == 0 && s->n_media == 2 && s->media[1].type == CV_MEDIUM_HOMOGENEOUS &&
               near(s->media[1].sigma_a.z, 1.5, 1e-6) && near(s->media[1].sigma_s.x, 0.5, 1e-6) &&
               near(s->media[1].sigma_a.w, 0.25, 1e-6) && near(s->media[1].Le.y, 2, 1e-6) &&
               s->media[1].emissive,
           "a homogeneous medium is read: sigma_a, sigma_s (default 1) times scale, g, Le times Lescale");
    tap_ok(s && tri_mat(s, 0)->media == CV_MEDIA_WORD(1u, 0u) && tri_mat(s, 1)->media == 0 &&
               tri_mat(s, 0)->type == tri_mat(s, 1)->type,
           "MediumInterface inside outside marks the surface's material copy; one name is no transition");
    cv_scene_destroy(&s);
    s = ok_load("MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\nMediumInterface \"\" \"fog\"\n"
                "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n" TRI, "camera medium");
    tap_ok(s && s->camera_medium == 1, "the camera sits in the outside medium current at Camera");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nMakeNamedMedium \"a\" \"string type\" \"cloud\"\n"
                "MakeNamedMedium \"b\" \"string type\" \"homogeneous\" \"string preset\" \"Ketchup\"\n"
                "MediumInterface \"c\" \"\"\n" TRI, "cloud, preset, unknown medium");
    tap_ok(s && s->warnings == 1 && s->media[1].type == CV_MEDIUM_CLOUD &&
               s->media[2].type == CV_MEDIUM_HOMOGENEOUS,
           "clouds and presets are read; unknown media names are reported (%u warnings)",
           s ? s->warnings : 0);
    cv_scene_destroy(&s);
}

/* A homogeneous medium's "preset": pbrt-v4's measured media, before
 * sigma_a and sigma_s, times scale; names it does not know. */
static void test_medium_presets(void)
{
    struct cv_scene *s;
    s = ok_load("WorldBegin\nMakeNamedMedium \"k\" \"string type\" \"homogeneous\"\n"
                "  \"string preset\" \"Ketchup\" \"float scale\" 2 \"float g\" 0.5\n"
                "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"string preset\" \"Lowfat Milk\"\n"
                "MakeNamedMedium \"e\" \"string type\" \"homogeneous\" \"string preset\" \"\"\n"
                "  \"rgb sigma_a\" [0.5 0.5 0.5]\n", "presets");
    tap_ok(s && s->warnings == 0 && s->n_media == 4 &&
               near(s->media[1].sigma_a.x, 0.122, 1e-6) && near(s->media[1].sigma_a.z, 2.9, 1e-6) &&
               near(s->media[1].sigma_s.x, 0.36, 1e-6) && near(s->media[1].sigma_s.y, 0.14, 1e-6) &&
               near(s->media[1].sigma_a.w, 0.5, 1e-6) && near(s->media[2].sigma_s.z, 2.532, 1e-6) &&
               near(s->media[2].sigma_a.y, 0.00575, 1e-9) && near(s->media[3].sigma_a.x, 0.5, 0) &&
               near(s->media[3].sigma_s.x, 1, 0),
           "a preset's sigma_a and sigma_s (per mm, as pbrt-v4's table) times scale; \"\" is none");
    cv_scene_destroy(&s);
    /* pbrt-v4 reads no sigma_a or sigma_s beside a preset it finds (they
     * are unused parameters there), and no preset on other media */
    s = ok_load("WorldBegin\nMakeNamedMedium \"k\" \"string type\" \"homogeneous\"\n"
                "  \"string preset\" \"Skin1\" \"rgb sigma_a\" [5 5 5]\n", "preset and sigma_a");
    tap_ok(s && s->warnings == 1 && near(s->media[1].sigma_a.x, 0.032, 1e-7) &&
               near(s->media[1].sigma_s.z, 1.01, 1e-6),
           "the preset wins over sigma_a, which is reported unused (%u warnings)", s ? s->warnings : 0);
    cv_scene_destroy(&s);
    const char *head = "WorldBegin\nMakeNamedMedium \"m\" \"string type\" ";
    char text[512];
    snprintf(text, sizeof(text), "%s\"homogeneous\"\n  \"float scale\" 2 \"string preset\" \"Ketchupp\"\n",
             head);
    fails(text, false, "main.pbrt:3:19: medium \"m\": unknown preset \"Ketchupp\"",
          "an unknown preset (at the parameter)");
    snprintf(text, sizeof(text), "%s\"homogeneous\" \"string preset\" \"wholemilk\"\n", head);
    fails(text, false, "medium \"m\": unknown preset \"wholemilk\"", "a preset's name in the wrong case");
    snprintf(text, sizeof(text), "%s\"homogeneous\" \"string preset\" \"Skin1\"\n  \"rgb sigma_s\" [1 1 1]\n",
             head);
    fails(text, true, "main.pbrt:3:3: MakeNamedMedium: parameter \"rgb sigma_s\" unused",
          "sigma_s beside a preset with --strict");
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"float density\" [1]\n  \"string preset\" \"Skin1\"\n",
             head);
    fails(text, true, "main.pbrt:3:3: MakeNamedMedium: parameter \"string preset\" unused",
          "a preset on a grid medium (pbrt-v4 reads none there) with --strict");
    snprintf(text, sizeof(text), "%s\"homogeneous\" \"string preset\" \"Skin1\" \"float scale\" -1\n", head);
    fails(text, false, "medium \"m\": sigma_a and sigma_s must be finite and not negative",
          "a preset with a negative scale");
}

/* pbrt-v4's cloud medium: what it becomes, and broken parameters. */
static void test_cloud_media(void)
{
    struct cv_scene *s;
    s = ok_load("WorldBegin\nTranslate 1 0 0\nMakeNamedMedium \"c\" \"string type\" \"cloud\"\n"
                "  \"float density\" 0.7 \"float wispiness\" 2 \"float frequency\" 9 \"float g\" -0.25\n"
                "  \"point3 p0\" [2 0 -1] \"point3 p1\" [0 4 1] \"rgb sigma_a\" [1 2 3] \"rgb sigma_s\" [0.5 4 1]\n"
                "MakeNamedMedium \"d\" \"string type\" \"cloud\"\n" TRI, "clouds");
    if (s && s->n_media == 3) {
        const CvMedium *m = &s->media[1], *d = &s->media[2];
        const float *q = s->medium_grids + m->grids.x, *qd = s->medium_grids + d->grids.x;
        const float *maj = s->medium_grids + m->res.w;
        const uint32_t cells = CV_MAJORANT_RES * CV_MAJORANT_RES * CV_MAJORANT_RES;
        bool flat = true;
        for (uint32_t i = 0; i < cells; i++)
            flat = flat && maj[i] == maj[0];
        /* render (2, 2, 0) is medium (1, 2, 0): the bounds [0,2]x[0,4]x[-1,1] put it at (0.5, 0.5, 0.5) */
        double g = m->to_grid[1].x * 2 + m->to_grid[1].y * 2 + m->to_grid[1].w;
        tap_ok(s->warnings == 0 && m->type == CV_MEDIUM_CLOUD && !m->emissive &&
                   near(m->sigma_a.y, 2, 0) && near(m->sigma_s.y, 4, 0) && near(m->sigma_a.w, -0.25, 1e-7) &&
                   near(q[0], 0.7, 1e-7) && near(q[1], 2, 0) && near(q[2], 9, 0) && near(q[3], 0, 0) &&
                   near(q[4], 0, 0) && near(q[5], -1, 0) && near(q[6], 2, 0) && near(q[7], 4, 0) &&
                   near(q[8], 2, 0) && near(g, 0.5, 1e-6) && flat &&
                   near(maj[0], 6 * (1 + 1e-5), 1e-5) && m->grids.y == CV_NO_GRID &&
                   m->temperature_grids.x == CV_NO_GRID,
               "a cloud is read: sigma_a, sigma_s, g, density, wispiness, frequency, bounds p0 p1 "
               "under the CTM, majorants the largest sigma_t (%g)", maj[0]);
        tap_ok(d->type == CV_MEDIUM_CLOUD && near(qd[0], 1, 0) && near(qd[1], 1, 0) &&
                   near(qd[2], 5, 0) && near(qd[6], 1, 0) && near(d->sigma_a.x, 1, 0) &&
                   near(d->sigma_s.z, 1, 0) && near(d->sigma_a.w, 0, 0),
               "a cloud's defaults are pbrt-v4's (density 1, wispiness 1, frequency 5, sigma 1, "
               "bounds 0 to 1, g 0)");
    }
    cv_scene_destroy(&s);
    const char *head = "WorldBegin\nMakeNamedMedium \"c\" \"string type\" ";
    char text[512];
    snprintf(text, sizeof(text), "%s\"cloud\" \"rgb sigma_s\" [1 -1 1]\n", head);
    fails(text, false, "main.pbrt:2:1: medium \"c\": sigma_a and sigma_s must be finite and not negative",
          "a cloud's negative sigma_s");
    snprintf(text, sizeof(text), "%s\"cloud\"\n  \"point3 p0\" [0 0 1] \"point3 p1\" [1 1 1]\n", head);
    fails(text, false, "main.pbrt:2:1: medium \"c\": its bounds p0 p1 are empty along axis 2",
          "a cloud's empty bounds");
    snprintf(text, sizeof(text), "%s\"cloud\"\n  \"float frequency\" 1e300\n", head);
    fails(text, false, "main.pbrt:3:3: medium \"c\": \"frequency\" is 1e+300; it must be finite",
          "a cloud's frequency beyond a float");
    snprintf(text, sizeof(text), "%s\"cloud\" \"float g\" 1\n", head);
    fails(text, true, "medium \"c\": g 1 is outside (-1, 1)", "a cloud's g of 1 with --strict");
    /* pbrt-v4's cloud reads no scale, Le or preset */
    snprintf(text, sizeof(text), "%s\"cloud\"\n  \"float scale\" 2\n", head);
    fails(text, true, "main.pbrt:3:3: MakeNamedMedium: parameter \"float scale\" unused",
          "a cloud's scale with --strict");
    snprintf(text, sizeof(text), "%s\"cloud\"\n  \"rgb Le\" [1 1 1]\n", head);
    fails(text, true, "main.pbrt:3:3: MakeNamedMedium: parameter \"rgb Le\" unused",
          "a cloud's Le with --strict");
}

/* pbrt-v4's grid media: what they become, and broken grids. */
static void test_grid_media(void)
{
    struct cv_scene *s;
    s = ok_load("WorldBegin\nTranslate 1 0 0\nMakeNamedMedium \"g\" \"string type\" \"uniformgrid\"\n"
                "  \"integer nx\" 2 \"integer ny\" 1 \"integer nz\" 3 \"float density\" [0 1 2 3 4 5]\n"
                "  \"point3 p0\" [2 0 -1] \"point3 p1\" [0 4 1] \"rgb sigma_a\" [1 2 3] \"float scale\" 2\n"
                "  \"float g\" -0.5 \"rgb Le\" [1 1 1]\n" TRI, "uniformgrid");
    if (s && s->n_media == 2) {
        const CvMedium *m = &s->media[1];
        /* render (2, 2, 0) is medium (1, 2, 0): the bounds [0,2]x[0,4]x[-1,1] put it at (0.5, 0.5, 0.5) */
        double g[3];
        for (int a = 0; a < 3; a++) {
            const cv_vec4 *r = &m->to_grid[a];
            g[a] = r->x * 2 + r->y * 2 + r->z * 0 + r->w;
        }
        tap_ok(s->warnings == 0 && m->type == CV_MEDIUM_UNIFORMGRID && m->res.x == 2 &&
                   m->res.y == 1 && m->res.z == 3 && near(m->sigma_a.z, 6, 1e-6) &&
                   near(m->sigma_s.x, 2, 1e-6) && near(m->sigma_a.w, -0.5, 1e-6) && m->emissive &&
                   m->grids.x == m->grids.y && m->grids.w == 0 && m->le_res.x == 1 &&
                   near(s->medium_grids[m->grids.x + 5], 5, 0) &&
                   near(s->medium_grids[m->grids.z], 1, 0),
               "a uniformgrid is read: density grid, sigma times scale, g, Le with pbrt-v4's "
               "one-sample Lescale grid");
        tap_ok(near(g[0], 0.5, 1e-6) && near(g[1], 0.5, 1e-6) && near(g[2], 0.5, 1e-6),
               "its transform is the CTM at MakeNamedMedium, then the bounds (corners in any "
               "order): %g %g %g", g[0], g[1], g[2]);
        size_t maj = m->res.w, nmaj = CV_MAJORANT_RES * CV_MAJORANT_RES * CV_MAJORANT_RES;
        tap_ok(maj + nmaj == s->n_medium_grids &&
                   near(s->medium_grids[maj + nmaj - 1], 5 * 8 * (1 + 1e-5), 1e-4),
               "its majorant grid follows the samples; the last cell bounds density 5 times "
               "sigma_t 8 (%g)", s->medium_grids[maj + nmaj - 1]);
    }
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"rgbgrid\" \"integer nx\" 2\n"
                "  \"rgb sigma_s\" [1 2 3 4 5 6] \"float scale\" 0.5 \"float Lescale\" 3\n" TRI,
                "rgbgrid");
    tap_ok(s && s->warnings == 0 && s->n_media == 2 && s->media[1].type == CV_MEDIUM_RGBGRID &&
               s->media[1].grids.x == CV_NO_GRID && s->media[1].grids.z == CV_NO_GRID &&
               s->media[1].grids.w == 1 && !s->media[1].emissive &&
               near(s->media[1].sigma_a.x, 0.5, 1e-6) &&
               near(s->medium_grids[s->media[1].grids.y + 4], 5, 0),
           "an rgbgrid is read: RGB sigma_s, no sigma_a grid (1 times scale), no emission");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"uniformgrid\" \"integer nx\" 2\n"
                "  \"float density\" [1 1] \"float temperature\" [1000 2000]\n"
                "  \"float temperaturecutoff\" 100 \"float temperaturescale\" 2\n" TRI,
                "uniformgrid with a temperature grid");
    tap_ok(s && s->warnings == 0 && s->media[1].emissive &&
               s->media[1].temperature_grids.x != CV_NO_GRID &&
               near(s->medium_grids[s->media[1].temperature_grids.x + 1], 2000, 0) &&
               near(s->media[1].temperature.x, 100, 0) && near(s->media[1].temperature.y, 2, 0) &&
               near(s->media[1].temperature.z, 3800, 1e-3) &&
               s->media[1].temperature_grids.y + 3 * CV_BLACKBODY_STEPS <= s->n_medium_grids,
           "a temperature grid emits: offset (temperaturecutoff, pbrt-v4's old name), scale, "
           "a blackbody table up to the hottest lookup (3800 K)");
    cv_scene_destroy(&s);
    const char *head = "WorldBegin\nMakeNamedMedium \"g\" \"string type\" ";
    char text[512];
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"integer nx\" 2\n  \"float density\" [1 2 3]\n", head);
    fails(text, false, "main.pbrt:3:3: medium \"g\": \"density\" has 3 values; nx*ny*nz = 2",
          "a density grid of the wrong size");
    snprintf(text, sizeof(text), "%s\"uniformgrid\"\n  \"integer ny\" -2 \"float density\" [1]\n", head);
    fails(text, false, "main.pbrt:3:3: medium \"g\": \"ny\" is -2", "a negative grid size");
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"integer nz\" 0 \"float density\" [1]\n", head);
    fails(text, false, "main.pbrt:2:49: medium \"g\": \"nz\" is 0", "a grid size of 0");
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"integer nx\" 2\n  \"float density\" [1 -2]\n", head);
    fails(text, false, "main.pbrt:3:3: medium \"g\": \"density\" value 1 is -2", "a negative density");
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"float density\" [1]\n  \"float Lescale\" [1 2]\n", head);
    fails(text, false, "main.pbrt:3:3: medium \"g\": \"Lescale\" has 2 values", "an Lescale grid of the wrong size");
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"float density\" [1]\n  \"float temperature\" [1 2]\n", head);
    fails(text, false, "main.pbrt:3:3: medium \"g\": \"temperature\" has 2 values", "a temperature grid of the wrong size");
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"float density\" [1] \"rgb Le\" [1 1 1]\n"
             "  \"float temperature\" [1000]\n", head);
    fails(text, false, "main.pbrt:2:1: medium \"g\": both \"Le\" and \"temperature\"", "Le beside a temperature grid");
    snprintf(text, sizeof(text), "%s\"uniformgrid\" \"integer nx\" 2\n", head);
    fails(text, false, "main.pbrt:2:1: medium \"g\": a uniformgrid needs \"float density\"", "no density");
    snprintf(text, sizeof(text), "%s\"rgbgrid\" \"integer nx\" 2\n  \"rgb sigma_a\" [1 2 3 4 5 6]\n"
             "  \"rgb sigma_s\" [1 2 3]\n", head);
    fails(text, false, "main.pbrt:4:3: medium \"g\": \"sigma_s\" has 3 values; nx*ny*nz = 2 needs 6",
          "RGB grids of different sizes");
    snprintf(text, sizeof(text), "%s\"rgbgrid\" \"rgb Le\" [1 2 3]\n", head);
    fails(text, false, "main.pbrt:2:1: medium \"g\": an rgbgrid needs \"rgb sigma_a\" or", "an rgbgrid without sigma");
    snprintf(text, sizeof(text), "%s\"rgbgrid\" \"rgb sigma_s\" [1 2 3] \"rgb Le\" [1 2 3]\n", head);
    fails(text, false, "main.pbrt:2:1: medium \"g\": an rgbgrid with \"Le\" needs", "Le without sigma_a");
    snprintf(text, sizeof(text), "%s\"rgbgrid\" \"rgb sigma_s\" [1 2 3]\n  \"point3 p0\" [0 1 0] \"point3 p1\" [1 1 1]\n", head);
    fails(text, false, "main.pbrt:2:1: medium \"g\": its bounds p0 p1 are empty along axis 1", "empty bounds");
}

static void test_settings(void)
{
    struct cv_scene *s = ok_load(
        "Film \"rgb\" \"integer xresolution\" [ 64 ] \"integer yresolution\" [ 32 ]"
        " \"float cropwindow\" [ 0 0.5 0 1 ] \"string filename\" \"out.exr\" \"float iso\" 200 \"float exposuretime\" 0.5\n"
        "Sampler \"halton\" \"integer pixelsamples\" 8\nPixelFilter \"box\" \"float xradius\" 0.5 \"float yradius\" 0.5\n"
        "Integrator \"volpath\" \"integer maxdepth\" [ 7 ]\nAccelerator \"bvh\"\nCamera \"perspective\"\nWorldBegin\n",
        "Film/Sampler/PixelFilter/Integrator/Accelerator");
    if (s) {
        const struct cv_render_settings *st = &s->settings;
        tap_ok(st->width == 64 && st->height == 32 && st->spp == 8 && st->max_depth == 7, "resolution, spp, maxdepth");
        tap_ok(strcmp(st->integrator, "volpath") == 0 && strcmp(st->sampler, "halton") == 0 &&
               strcmp(st->film_filename, "out.exr") == 0, "names as written");
        tap_ok(st->filter == CV_FILTER_BOX && near(st->filter_radius[0], 0.5, 1e-6), "filter");
        tap_ok(s->camera.crop.x == 32 && s->camera.crop.y == 32 && s->camera.film.z == 0, "crop window in pixels");
        tap_ok(near(st->exposure, 1, 1e-6), "iso 200 x exposuretime 0.5");
    }
    cv_scene_destroy(&s);
    s = ok_load("Film \"image\" \"integer xresolution\" 10 \"integer yresolution\" 10\n"
                "PixelFilter \"gaussian\" \"float xwidth\" 2 \"float ywidth\" 2\nWorldBegin\n", "v3 Film image");
    tap_ok(s && s->settings.width == 10 && s->settings.filter == CV_FILTER_GAUSSIAN &&
           near(s->settings.filter_radius[1], 2, 1e-6) &&
           near(s->settings.filter_sigma, CV_FILTER_GAUSSIAN_SIGMA, 1e-6), "v3 widths");
    cv_scene_destroy(&s);
    s = ok_load("PixelFilter \"gaussian\" \"float alpha\" 8\nWorldBegin\n", "v3 gaussian alpha");
    tap_ok(s && s->warnings == 0 && near(s->settings.filter_sigma, 0.25, 1e-6),
           "v3 gaussian alpha 8: sigma 1 / sqrt(2 alpha) = 0.25 (%g)",
           s ? s->settings.filter_sigma : 0);
    cv_scene_destroy(&s);
    s = ok_load("PixelFilter \"gaussian\" \"float alpha\" 2\nWorldBegin\n", "v3 default alpha");
    tap_ok(s && near(s->settings.filter_sigma, CV_FILTER_GAUSSIAN_SIGMA, 1e-6),
           "v3 gaussian alpha 2: v4's default sigma");
    cv_scene_destroy(&s);
    fails("PixelFilter \"gaussian\" \"float alpha\" 0\nWorldBegin\n", false, "must be positive",
          "gaussian alpha 0");
    s = ok_load("Film \"rgb\" \"string sensor\" \"cie1931\" \"float whitebalance\" 0 "
                "\"float diagonal\" 35\nWorldBegin\n", "film defaults");
    tap_ok(s && s->warnings == 0, "film sensor, whitebalance at pbrt-v4's defaults: no warning");
    cv_scene_destroy(&s);
    s = ok_load("Film \"rgb\" \"string sensor\" \"canon_eos_5d_mkiv\" \"float whitebalance\" 5000 "
                "\"float maxcomponentvalue\" 10 \"integer pixelbounds\" [0 8 0 8]\nWorldBegin\n",
                "film sensor");
    tap_ok(s && s->warnings == 4, "film sensor, whitebalance, maxcomponentvalue and pixelbounds: "
           "four warnings (%u)", s ? s->warnings : 0);
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nTexture \"r\" \"float\" \"constant\" \"float value\" 0.1\n"
                "Material \"coatedconductor\" \"texture conductor.roughness\" \"r\"\n" TRI,
                "textured coatedconductor base");
    tap_ok(s && s->warnings == 1 && s->n_materials >= 1 &&
               near(s->materials[s->n_materials - 1].roughness2.x, 0, 1e-6),
           "coatedconductor: a textured conductor roughness is a warning, the base smooth (%u)",
           s ? s->warnings : 0);
    cv_scene_destroy(&s);
}

/* How many of triangles t0..t1-1 carry a uv at each vertex that equals
 * (x - dx, y): on a unit square, pbrt-v4's patch (u, v). */
static int uv_is_xy(const struct cv_scene *s, uint32_t t0, uint32_t t1, float dx)
{
    int n = 0;
    for (uint32_t t = t0; s && t < s->n_triangles && t < t1; t++) {
        const uint32_t *ix = &s->triangles[t].idx.x;
        bool ok = (s->triangles[t].idx.w & CV_TRI_HAS_UV) != 0;
        for (int k = 0; k < 3; k++) {
            const CvVertex *v = &s->vertices[ix[k]];
            ok = ok && v->pos_u.w == v->pos_u.x - dx && v->nrm_v.w == v->pos_u.y;
        }
        n += ok;
    }
    return n;
}

static void test_shapes(void)
{
    struct cv_scene *s;
    s = ok_load("WorldBegin\nShape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n", "bilinearmesh");
    tap_ok(s && s->n_triangles == 2, "bilinear patch -> 2 triangles");
    int uv_ok = uv_is_xy(s, 0, 2, 0);
    tap_ok(uv_ok == 2, "bilinear patch without uv: both triangles take the patch's (u, v) "
           "(%d of 2)", uv_ok);
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]"
                " \"point2 uv\" [0 0 2 0 0 2 2 2]\n", "bilinearmesh with uv");
    tap_ok(s && s->n_triangles == 2 && s->vertices[s->triangles[1].idx.y].pos_u.w == 2,
           "bilinear patch with uv: its own");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"sphere\" \"float radius\" 2\n", "sphere");
    tap_ok(s && s->n_triangles > 1000 && near(s->bounds_max[2], 2, 1e-5) && near(s->bounds_min[0], -2, 1e-3),
           "sphere tessellated to its radius");
    tap_ok(s && (s->triangles[0].idx.w & CV_TRI_HAS_NORMAL) && (s->triangles[0].idx.w & CV_TRI_HAS_UV),
           "sphere has normals and uv");
    if (s) {
        /* outward: geometric normal of a triangle agrees with its vertex normal */
        const CvTriangle *t = &s->triangles[s->n_triangles / 2];
        const cv_vec4 *a = &s->vertices[t->idx.x].pos_u, *b = &s->vertices[t->idx.y].pos_u,
                      *c = &s->vertices[t->idx.z].pos_u;
        double e1[3] = {b->x - a->x, b->y - a->y, b->z - a->z}, e2[3] = {c->x - a->x, c->y - a->y, c->z - a->z};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const cv_vec4 *vn = &s->vertices[t->idx.x].nrm_v;
        tap_ok(n[0] * vn->x + n[1] * vn->y + n[2] * vn->z > 0, "sphere winding faces outward");
    }
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"disk\" \"float radius\" 1 \"float height\" 0.5\n", "disk");
    tap_ok(s && s->n_triangles >= 64 && near(s->bounds_min[2], 0.5, 1e-6), "disk");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"cylinder\" \"float radius\" 1 \"float zmin\" 0 \"float zmax\" 3\n", "cylinder");
    tap_ok(s && s->n_triangles >= 128 && near(s->bounds_max[2], 3, 1e-6), "cylinder");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"loopsubdiv\" \"integer levels\" 2 \"point3 P\" [0 0 0 1 0 0 0 1 0 0 0 1]"
                " \"integer indices\" [0 2 1 0 1 3 0 3 2 1 2 3]\n", "loopsubdiv");
    tap_ok(s && s->n_triangles == 4 * 16 && (s->triangles[0].idx.w & CV_TRI_HAS_NORMAL),
           "loopsubdiv: 4^levels triangles with normals");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"heightfield\" \"integer nu\" 3 \"integer nv\" 2 \"float Pz\" [0 1 0 0 2 0]\n",
                "heightfield");
    tap_ok(s && s->n_triangles == 4 && near(s->bounds_max[2], 2, 1e-6), "heightfield grid");
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"curves\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]\n", "curves");
    tap_ok(s && s->n_triangles == 0 && s->warnings == 1, "curves: warning, nothing added");
    cv_scene_destroy(&s);
    s = ok_load("Integrator \"path\" \"bool regularize\" true\nWorldBegin\n", "regularize");
    tap_ok(s && s->warnings == 1, "Integrator regularize true: a warning (%u)", s ? s->warnings : 0);
    cv_scene_destroy(&s);
    s = ok_load("Integrator \"path\" \"bool regularize\" false \"string lightsampler\" \"power\"\n"
                "WorldBegin\n", "regularize false");
    tap_ok(s && s->warnings == 0, "Integrator regularize false, a light sampler: no warning (%u)",
           s ? s->warnings : 0);
    cv_scene_destroy(&s);
    s = ok_load("Sampler \"sobol\" \"integer pixelsamples\" 20000000\nWorldBegin\n", "huge pixelsamples");
    tap_ok(s && s->settings.spp == 16777216 && s->warnings == 1,
           "pixelsamples past the renderer's limit: warning, capped (%u)", s ? s->settings.spp : 0);
    cv_scene_destroy(&s);
    th_write_str("quad.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    s = ok_load("WorldBegin\nShape \"plymesh\" \"string filename\" \"quad.ply\"\n", "plymesh");
    tap_ok(s && s->n_triangles == 2, "plymesh quad -> 2 triangles");
    uv_ok = uv_is_xy(s, 0, 2, 0);
    tap_ok(uv_ok == 2, "plymesh quad without uv: both triangles take the patch's (u, v), as "
           "pbrt-v4's bilinear patch (%d of 2)", uv_ok);
    cv_scene_destroy(&s);
    /* a triangle, a quad (the unit square moved by 2 in x), a triangle */
    th_write_str("mixed.ply", "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\n"
                              "property float y\nproperty float z\nelement face 3\n"
                              "property list uchar int vertex_indices\nend_header\n"
                              "0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 0\n3 1 0\n2 1 0\n"
                              "3 0 1 2\n4 3 4 5 6\n3 2 1 0\n");
    s = ok_load("WorldBegin\nShape \"plymesh\" \"string filename\" \"mixed.ply\"\n", "plymesh, mixed");
    tap_ok(s && s->n_triangles == 4, "plymesh of two triangles and a quad -> 4 triangles");
    uv_ok = uv_is_xy(s, 1, 3, 2);
    int tri_ok = 0;
    static const float tri_uv[3][2] = {{0, 0}, {1, 0}, {1, 1}};
    for (uint32_t t = 0; s && t < s->n_triangles; t += 3) {
        bool ok = (s->triangles[t].idx.w & CV_TRI_HAS_UV) != 0;
        for (int k = 0; k < 3; k++) {
            const CvVertex *v = &s->vertices[(&s->triangles[t].idx.x)[k]];
            ok = ok && v->pos_u.w == tri_uv[k][0] && v->nrm_v.w == tri_uv[k][1];
        }
        tri_ok += ok;
    }
    tap_ok(uv_ok == 2 && tri_ok == 2, "... its quad's triangles take the patch's (u, v) (%d of 2), "
           "its triangles a triangle's default (0, 0) (1, 0) (1, 1) (%d of 2)", uv_ok, tri_ok);
    cv_scene_destroy(&s);
    th_write_str("pentagon.ply", "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 1\n"
                                 "property list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n1.3 1 0\n0.5 1.6 0\n-0.3 1 0\n5 0 1 2 3 4\n");
    s = ok_load("WorldBegin\nShape \"plymesh\" \"string filename\" \"pentagon.ply\"\n", "plymesh, pentagon");
    tap_ok(s && s->n_triangles == 3 && s->warnings == 1,
           "plymesh pentagon: a fan of 3 triangles and a warning, since pbrt-v4 skips it (%u)",
           s ? s->warnings : 0);
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nMaterial \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]"
                " \"float alpha\" 0.25 \"float uv\" [0 0 1 0 0 1]\n", "alpha on a shape, v3 float uv");
    tap_ok(s && near(tri_mat(s, 0)->alpha, 0.25, 1e-6) && (s->triangles[0].idx.w & CV_TRI_HAS_UV) &&
           near(s->vertices[1].pos_u.w, 1, 1e-6), "alpha becomes a material cut-out; uv stored");
    cv_scene_destroy(&s);
}

static double lum(cv_vec4 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

static void test_materials(void)
{
    th_write_str("flat.spd", "# flat\n300 2.0\n800 2.0\n");
    struct cv_scene *s = ok_load(
        "WorldBegin\n"
        "MakeNamedMaterial \"a\" \"string type\" \"matte\" \"rgb Kd\" [0.1 0.2 0.3]\n"
        "MakeNamedMaterial \"b\" \"string type\" [ \"conductor\" ] \"spectrum eta\" \"metal-Au-eta\""
        " \"spectrum k\" \"metal-Au-k\" \"float roughness\" 0.25\n"
        "MakeNamedMaterial \"c\" \"string type\" \"dielectric\" \"spectrum eta\" \"glass-BK7\"\n"
        "MakeNamedMaterial \"d\" \"string type\" \"glass\" \"float index\" 1.33\n"
        "MakeNamedMaterial \"e\" \"string type\" \"metal\" \"spectrum eta\" \"flat.spd\""
        " \"float uroughness\" 0.1 \"float vroughness\" 0.2 \"bool remaproughness\" \"false\"\n"
        "MakeNamedMaterial \"f\" \"string type\" \"mix\" \"string materials\" [\"a\" \"b\"] \"float amount\" 0.3\n"
        "MakeNamedMaterial \"g\" \"string type\" \"plastic\" \"color Kd\" [0.5 0.5 0.5]\n"
        "MakeNamedMaterial \"h\" \"string type\" \"coateddiffuse\" \"float roughness\" 0.04\n"
        "MakeNamedMaterial \"i\" \"string type\" \"coatedconductor\" \"float conductor.roughness\" 0.01"
        " \"float interface.eta\" 1.4\n"
        "MakeNamedMaterial \"j\" \"string type\" \"mirror\"\n"
        "MakeNamedMaterial \"k\" \"string type\" \"substrate\"\n"
        "MakeNamedMaterial \"l\" \"string type\" \"uber\"\n"
        "MakeNamedMaterial \"m\" \"string type\" \"diffusetransmission\"\n"
        "MakeNamedMaterial \"n\" \"string type\" \"interface\"\n"
        "MakeNamedMaterial \"o\" \"string type\" \"diffuse\" \"spectrum reflectance\" [400 0.5 500 0.5 700 0.5]\n"
        "MakeNamedMaterial \"p\" \"string type\" \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"c\"\n"
        "MakeNamedMaterial \"q\" \"string type\" \"thindielectric\"\n"
        "NamedMaterial \"b\"\n" TRI,
        "all material types");
    if (s) {
        const CvMaterial *m = s->materials;
        tap_ok(s->n_materials == 17, "17 materials (%u)", s->n_materials);
        tap_ok(m[0].type == CV_MAT_DIFFUSE && near(m[0].reflectance.y, 0.2, 1e-6), "matte Kd");
        tap_ok(m[1].type == CV_MAT_CONDUCTOR && near(m[1].eta.x, 0.143119, 1e-5) &&
               near(m[1].roughness.x, 0.5, 1e-6), "conductor: named Au eta, v4 remap sqrt");
        tap_ok(m[2].type == CV_MAT_DIELECTRIC && near(m[2].eta.x, 1.5185, 1e-3), "dielectric glass-BK7");
        tap_ok(near(m[3].eta.x, 1.33, 1e-6), "v3 glass index");
        tap_ok(near(lum(m[4].eta), 2.0, 0.01) && near(m[4].roughness.y, 0.2, 1e-6), ".spd file; no remap; vroughness");
        tap_ok(m[5].type == CV_MAT_MIX && m[5].mix_a == 0 && m[5].mix_b == 1 && near(m[5].amount, 0.3, 1e-6), "mix (v4)");
        tap_ok(m[6].type == CV_MAT_PLASTIC && near(m[6].specular.x, 0.25, 1e-6), "plastic defaults");
        tap_ok(m[7].type == CV_MAT_COATED_DIFFUSE && near(m[7].roughness.x, 0.2, 1e-6) && near(m[7].eta.x, 1.5, 1e-6),
               "coateddiffuse");
        tap_ok(m[8].type == CV_MAT_COATED_CONDUCTOR && near(m[8].roughness2.x, 0.1, 1e-6) && near(m[8].eta.w, 1.4, 1e-6),
               "coatedconductor");
        tap_ok(m[9].type == CV_MAT_MIRROR && near(m[9].reflectance.x, 0.9, 1e-6), "mirror");
        tap_ok(m[10].type == CV_MAT_COATED_DIFFUSE &&
                   strstr(th_log_text(), "substrate: rendered as coated diffuse") != NULL,
               "substrate: coated diffuse, with a warning");
        tap_ok(m[11].type == CV_MAT_PLASTIC, "uber");
        tap_ok(m[12].type == CV_MAT_DIFFUSE_TRANSMISSION && near(m[12].specular.x, 0.25, 1e-6), "diffusetransmission");
        tap_ok(m[13].type == CV_MAT_INTERFACE, "interface");
        tap_ok(near(lum(m[14].reflectance), 0.5, 2e-3), "spectrum pairs keep their luminance (%g)", lum(m[14].reflectance));
        /* seen under D65, sRGB's white, as pbrt-v4 renders a reflectance
         * under an RGB light: a constant spectrum stays grey (under an
         * equal-energy white it read 0.60 0.47 0.45) */
        tap_ok(near(m[14].reflectance.x, 0.5, 1e-3) && near(m[14].reflectance.y, 0.5, 1e-3) &&
                   near(m[14].reflectance.z, 0.5, 1e-3),
               "a constant reflectance spectrum stays grey (%g %g %g)", m[14].reflectance.x,
               m[14].reflectance.y, m[14].reflectance.z);
        tap_ok(m[15].mix_a == 2 && m[15].mix_b == 0,
               "mix (v3 namedmaterial1/2): namedmaterial1 weighed by amount, as pbrt-v3 does");
        tap_ok(m[16].type == CV_MAT_THIN_DIELECTRIC, "thindielectric");
        tap_ok((s->triangles[0].idx.w & CV_TRI_MATERIAL_MASK) == 1, "NamedMaterial sets the triangle's material");
    }
    cv_scene_destroy(&s);
    /* an index that varies with wavelength is dispersion in pbrt-v4: one
     * value is rendered, with a warning at the parameter */
    static const struct {
        const char *eta;
        unsigned warnings;
    } disp[] = {
        {"\"spectrum eta\" \"glass-BK7\"", 1},
        {"\"spectrum eta\" [400 1.53 700 1.51]", 1},
        {"\"rgb eta\" [1.4 1.5 1.6]", 1},
        {"\"float eta\" 1.5", 0},
        {"\"spectrum eta\" [400 1.5 700 1.5]", 0},
        {"\"rgb eta\" [1.5 1.5 1.5]", 0},
    };
    for (size_t i = 0; i < sizeof(disp) / sizeof(disp[0]); i++) {
        char text[512];
        snprintf(text, sizeof(text), "WorldBegin\nMaterial \"dielectric\" %s\n" TRI, disp[i].eta);
        s = ok_load(text, disp[i].eta);
        if (s)
            tap_ok(s->warnings == disp[i].warnings &&
                       (!disp[i].warnings || strstr(th_log_text(), "main.pbrt:2:23: \"eta\" varies with wavelength")),
                   "%s: %u warnings (dispersion)", disp[i].eta, s->warnings);
        cv_scene_destroy(&s);
    }
}

/* pbrt-v4's hair material: defaults, and which colour parameter wins. */
static void test_hair_material(void)
{
    struct cv_scene *s = ok_load(
        "WorldBegin\n"
        "MakeNamedMaterial \"a\" \"string type\" \"hair\"\n"
        "MakeNamedMaterial \"b\" \"string type\" \"hair\" \"rgb sigma_a\" [0.1 0.2 0.3] \"rgb reflectance\" [0.5 0.5 0.5]"
        " \"float beta_m\" 0.2 \"float beta_n\" 0.4 \"float alpha\" 3 \"float eta\" 1.6\n"
        "MakeNamedMaterial \"c\" \"string type\" \"hair\" \"rgb reflectance\" [0.6 0.4 0.2] \"float eumelanin\" 2\n"
        "MakeNamedMaterial \"d\" \"string type\" \"hair\" \"float pheomelanin\" 0.7 \"float alpha\" 0\n"
        "NamedMaterial \"a\"\n" TRI,
        "hair materials");
    if (s) {
        const CvMaterial *m = s->materials;
        const char *log = th_log_text();
        tap_ok(s->n_materials == 4 && m[0].type == CV_MAT_HAIR && m[0].flags == 0 &&
                   near(m[0].reflectance.x, 1.3, 1e-6) && near(m[0].reflectance.y, 0, 1e-6) &&
                   near(m[0].roughness.x, 0.3, 1e-6) && near(m[0].roughness.y, 0.3, 1e-6) &&
                   near(m[0].roughness.z, 2, 1e-6) && near(m[0].eta.x, 1.55, 1e-6),
               "hair defaults: eumelanin 1.3, beta_m 0.3, beta_n 0.3, alpha 2, eta 1.55");
        tap_ok((m[1].flags & CV_MATF_HAIR_SIGMA_A) && near(m[1].reflectance.z, 0.3, 1e-6) &&
                   near(m[1].roughness.x, 0.2, 1e-6) && near(m[1].roughness.y, 0.4, 1e-6) &&
                   near(m[1].roughness.z, 3, 1e-6) && near(m[1].eta.x, 1.6, 1e-6) &&
                   strstr(log, "hair: ignoring \"reflectance\" since \"sigma_a\"") != NULL,
               "hair: sigma_a wins over reflectance, with a warning");
        tap_ok((m[2].flags & CV_MATF_HAIR_REFLECTANCE) && near(m[2].reflectance.x, 0.6, 1e-3) &&
                   strstr(log, "hair: ignoring \"eumelanin\" since \"reflectance\"") != NULL,
               "hair: reflectance wins over the melanins, with a warning");
        tap_ok(m[3].flags == 0 && near(m[3].reflectance.x, 0, 1e-6) && near(m[3].reflectance.y, 0.7, 1e-6),
               "hair: pheomelanin alone leaves eumelanin 0");
        tap_ok(near(m[3].roughness.z, 0, 1e-6) && m[3].alpha == 1 && m[3].alpha_tex < 0 &&
                   m[1].alpha == 1,
               "hair: alpha is the scales' tilt (0, 3), not a cut-out (alpha %g, %g)", m[3].alpha,
               m[1].alpha);
        tap_ok(strstr(log, "not supported; using diffuse") == NULL, "hair: no longer diffuse 0.5");
    }
    cv_scene_destroy(&s);
}

static void write_tga(const char *rel, int w, int h, const unsigned char *rgb)
{
    unsigned char hdr[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, (unsigned char)w, 0, (unsigned char)h, 0, 24, 0x20};
    size_t n = (size_t)w * h * 3;
    unsigned char *buf = malloc(18 + n);
    memcpy(buf, hdr, 18);
    for (size_t i = 0; i < (size_t)w * h; i++) { /* BGR */
        buf[18 + i * 3] = rgb[i * 3 + 2];
        buf[18 + i * 3 + 1] = rgb[i * 3 + 1];
        buf[18 + i * 3 + 2] = rgb[i * 3];
    }
    th_write(rel, buf, 18 + n);
    free(buf);
}

/* An 8-bit PNG (RGB, or RGBA with `alpha`) through libpng's simplified
 * API. */
static void write_png_as(const char *rel, int w, int h, const unsigned char *px, bool alpha)
{
    png_image im = {.version = PNG_IMAGE_VERSION, .width = (png_uint_32)w,
                    .height = (png_uint_32)h, .format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB};
    if (!png_image_write_to_file(&im, th_path(rel), 0, px, 0, NULL))
        tap_ok(false, "writing %s: %s", rel, im.message);
}

static void write_png(const char *rel, int w, int h, const unsigned char *rgb)
{
    write_png_as(rel, w, h, rgb, false);
}

static void write_pfm(const char *rel, int w, int h, float v)
{
    size_t count = (size_t)w * h * 3;
    float *rgb = malloc(count * sizeof(float));
    for (size_t i = 0; i < count; i++)
        rgb[i] = v;
    th_write_pfm(rel, w, h, rgb);
    free(rgb);
}

/* channels: IMF_WRITE_RGBA, or IMF_WRITE_Y / IMF_WRITE_YC (luminance,
 * with chroma) for the loader's other paths. */
static void write_exr_channels(const char *rel, int w, int h, float v, int channels)
{
    ImfHeader *hdr = ImfNewHeader();
    ImfHeaderSetDataWindow(hdr, 0, 0, w - 1, h - 1);
    ImfHeaderSetDisplayWindow(hdr, 0, 0, w - 1, h - 1);
    ImfOutputFile *out = ImfOpenOutputFile(th_path(rel), hdr, channels);
    ImfRgba *px = calloc((size_t)w * h, sizeof(ImfRgba));
    for (int i = 0; i < w * h; i++) {
        ImfFloatToHalf(v, &px[i].r);
        ImfFloatToHalf(v * 2, &px[i].g);
        ImfFloatToHalf(v * 4, &px[i].b);
        ImfFloatToHalf(1, &px[i].a);
    }
    if (out) {
        ImfOutputSetFrameBuffer(out, px, 1, (size_t)w);
        ImfOutputWritePixels(out, h);
        ImfCloseOutputFile(out);
    }
    free(px);
    ImfDeleteHeader(hdr);
}

static void write_exr(const char *rel, int w, int h, float v)
{
    write_exr_channels(rel, w, h, v, IMF_WRITE_RGBA);
}

static void test_textures(void)
{
    unsigned char px[2 * 2 * 3] = {255, 255, 255, 0, 0, 0, 128, 128, 128, 255, 0, 0};
    write_tga("t.tga", 2, 2, px);
    write_png("t.png", 2, 2, px);
    write_pfm("f.pfm", 4, 2, 0.5f);
    write_exr("e.exr", 8, 4, 0.25f);
    struct cv_scene *s = ok_load(
        "WorldBegin\nTexture \"e\" \"spectrum\" \"imagemap\" \"string filename\" \"e.exr\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"e\"\n" TRI, "EXR texture");
    if (s) {
        const CvTexture *t = &s->textures[s->n_textures - 1];
        float c[4];
        cv_scene_texel(s, t, 0, c);
        tap_ok(t->width == 8 && t->height == 4 && t->levels == 4 && !(t->flags & CV_TEXF_SRGB) &&
               (t->flags & CV_TEXF_RGBA32F) && c[0] == 0.25f && c[1] == 0.5f && c[2] == 1.0f &&
               c[3] == 1.0f, "EXR read as linear float RGBA (%g %g %g %g)", c[0], c[1], c[2], c[3]);
    }
    cv_scene_destroy(&s);
    /* luminance alone reads as grey; luminance-chroma through OpenEXR's
     * RGBA conversion (the colour 0.25, 0.5, 1 comes back near itself) */
    write_exr_channels("y.exr", 4, 2, 0.25f, IMF_WRITE_Y);
    write_exr_channels("yc.exr", 4, 2, 0.25f, IMF_WRITE_YC);
    const char *lum[2] = {"y.exr", "yc.exr"};
    float c2[2][4] = {{0}};
    for (int k = 0; k < 2; k++) {
        char text[512];
        snprintf(text, sizeof(text),
                 "WorldBegin\nTexture \"l\" \"spectrum\" \"imagemap\" \"string filename\" \"%s\"\n"
                 "Material \"diffuse\" \"texture reflectance\" \"l\"\n" TRI, lum[k]);
        s = ok_load(text, lum[k]);
        if (s)
            cv_scene_texel(s, &s->textures[s->n_textures - 1], 0, c2[k]);
        cv_scene_destroy(&s);
    }
    const float *y = c2[0], *yc = c2[1];
    tap_ok(y[0] > 0.3f && y[0] < 0.6f && y[0] == y[1] && y[1] == y[2] && y[3] == 1.0f,
           "EXR of Y alone reads as grey (%g %g %g %g)", y[0], y[1], y[2], y[3]);
    tap_ok(fabsf(yc[0] - 0.25f) < 0.03f && fabsf(yc[1] - 0.5f) < 0.03f && fabsf(yc[2] - 1.0f) < 0.06f,
           "EXR of Y and chroma reads back its colour (%g %g %g)", yc[0], yc[1], yc[2]);
    s = ok_load(
        "WorldBegin\n"
        "Texture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"t.tga\" \"float uscale\" 4"
        " \"string wrap\" \"clamp\"\n"
        "Texture \"lin\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\" \"string encoding\" \"linear\"\n"
        "Texture \"hdr\" \"float\" \"imagemap\" \"string filename\" \"f.pfm\"\n"
        "Texture \"ck\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [1 0 0] \"texture tex2\" \"img\"\n"
        "Texture \"k\" \"float\" \"constant\" \"float value\" 0.7\n"
        "Texture \"sc\" \"spectrum\" \"scale\" \"texture tex\" \"img\" \"float scale\" 0.5\n"
        "Texture \"sc3\" \"spectrum\" \"scale\" \"texture tex1\" \"img\" \"rgb tex2\" [2 2 2]\n"
        "Texture \"mx\" \"spectrum\" \"mix\" \"texture tex1\" \"img\" \"rgb tex2\" [0 0 1] \"texture amount\" \"k\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"sc\" \"texture displacement\" \"k\"\n" TRI,
        "textures");
    if (s) {
        const CvTexture *t = s->textures;
        int img = -1;
        for (uint32_t i = 0; i < s->n_textures; i++)
            if (t[i].type == CV_TEX_IMAGE && (t[i].flags & CV_TEXF_WRAP_CLAMP))
                img = (int)i;
        tap_ok(img >= 0 && t[img].width == 2 && t[img].levels == 2 && (t[img].flags & CV_TEXF_SRGB) &&
               near(t[img].uv_map.x, 4, 1e-6), "imagemap: size, mips, sRGB flag, uscale, wrap");
        if (img >= 0) {
            uint32_t w0 = s->texels[2 * t[img].offset];
            tap_ok((w0 & 0xffff) == 0x3c00, "white texel is half 1.0");
            uint32_t g = s->texels[2 * (t[img].offset + 2)];
            tap_ok(near(cv_half_to_float((uint16_t)(g & 0xffff)), 0.2158, 2e-3), "sRGB 128 decoded to linear");
            uint32_t top = s->texels[2 * (t[img].offset + 4)];
            tap_ok(near(cv_half_to_float((uint16_t)(top & 0xffff)), (1 + 0 + 0.2158 + 1) / 4, 3e-3),
                   "mip level 1 is the box average");
        }
        bool lin = false, hdr = false, ck = false, sc = false, mx = false;
        for (uint32_t i = 0; i < s->n_textures; i++) {
            if (t[i].type == CV_TEX_IMAGE && !(t[i].flags & CV_TEXF_SRGB) && t[i].width == 2)
                lin = true;
            if (t[i].type == CV_TEX_IMAGE && (t[i].flags & CV_TEXF_FLOAT) && t[i].width == 4)
                hdr = true;
            if (t[i].type == CV_TEX_CHECKERBOARD && near(t[i].value_a.x, 1, 1e-6) && t[i].tex_b >= 0)
                ck = true;
            if (t[i].type == CV_TEX_SCALE && near(t[i].value_b.x, 0.5, 1e-6) && t[i].tex_a >= 0)
                sc = true;
            if (t[i].type == CV_TEX_MIX && t[i].amount_tex >= 0 && near(t[i].value_b.z, 1, 1e-6))
                mx = true;
        }
        tap_ok(lin, "encoding linear of a PNG");
        tap_ok(s->warnings == 0, "no warning (%u)", s->warnings);
        tap_ok(hdr, "PFM float texture");
        tap_ok(ck && sc && mx, "checkerboard, scale, mix");
        const CvMaterial *m = tri_mat(s, 0);
        tap_ok(m->reflectance_tex >= 0 && s->textures[m->reflectance_tex].type == CV_TEX_SCALE &&
               m->displacement_tex >= 0, "material texture slots");
    }
    cv_scene_destroy(&s);
}

static void test_lights(void)
{
    write_pfm("env.pfm", 4, 2, 2.0f);
    write_pfm("oct.pfm", 2, 2, 1.0f);
    struct cv_scene *s = ok_load(
        "WorldBegin\n"
        "LightSource \"point\" \"rgb I\" [1 1 1] \"float power\" 100 \"point3 from\" [1 2 3]\n"
        "LightSource \"spot\" \"blackbody I\" 3000 \"float coneangle\" 20 \"float conedeltaangle\" 5\n"
        "LightSource \"distant\" \"color L\" [2 2 2] \"point from\" [0 0 0] \"point to\" [0 -1 0]\n"
        "LightSource \"infinite\" \"rgb L\" [0.5 0.5 0.5]\n"
        "LightSource \"infinite\" \"string mapname\" \"env.pfm\"\n"
        "LightSource \"infinite\" \"string filename\" \"oct.pfm\" \"float scale\" 3\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"float power\" 10 \"bool twosided\" true\n"
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 2 0 0 0 2 0] \"integer indices\" [0 1 2]\n"
        "AttributeEnd\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 4] \"float scale\" 0.5\n" TRI "AttributeEnd\n" TRI,
        "lights");
    if (s) {
        tap_ok(s->n_lights == 8, "8 lights (%u)", s->n_lights);
        const CvLight *l = s->lights;
        /* infinite lights first, each group in file order (scene.h) */
        tap_ok(l[3].type == CV_LIGHT_POINT && near(l[3].L.x, 100 / (4 * M_PI), 1e-4) && near(l[3].position.z, 3, 1e-6),
               "point light power and position");
        tap_ok(l[4].type == CV_LIGHT_SPOT && near(lum(l[4].L), 1, 1e-3) && near(l[4].direction.w, cos(20 * M_PI / 180), 1e-6) &&
               near(l[4].position.w, cos(15 * M_PI / 180), 1e-6), "spot: blackbody normalised, cone cosines");
        tap_ok(l[5].type == CV_LIGHT_DISTANT && near(l[5].direction.y, -1, 1e-6), "distant direction (travel)");
        tap_ok(l[0].type == CV_LIGHT_INFINITE, "infinite constant");
        tap_ok(l[1].type == CV_LIGHT_INFINITE_MAP && !(l[1].flags & CV_LIGHTF_EQUAL_AREA) && l[1].tex >= 0,
               "v3 lat-long map");
        tap_ok(l[2].type == CV_LIGHT_INFINITE_MAP && (l[2].flags & CV_LIGHTF_EQUAL_AREA) && near(l[2].L.x, 3, 1e-6),
               "v4 equal-area map with scale");
        tap_ok(l[6].type == CV_LIGHT_AREA && (l[6].flags & CV_LIGHTF_TWO_SIDED) && near(l[6].L.w, 2, 1e-6) &&
               near(l[6].L.x, 10 / (M_PI * 2 * 2), 1e-5), "area light: area in L.w, power over both sides");
        tap_ok(near(l[7].L.x, 2, 1e-6), "area light scale");
        tap_ok(s->n_triangles == 3 && s->tri_light[0] == 6 && s->tri_light[1] == 7 && s->tri_light[2] == -1,
               "tri_light maps emitting triangles to their light");
        bool pos = true;
        for (uint32_t i = 0; i < s->n_lights; i++)
            pos = pos && s->light_power[i] > 0;
        tap_ok(pos, "every light has a positive sampling power");
    }
    cv_scene_destroy(&s);
    /* pbrt-v4 normalises an image area light's "power" by the image's mean
     * luminance too; it reads "power" on point and spot lights alone, and
     * refuses "L" beside "filename" (Cavalry warns) */
    unsigned char grey[2 * 2 * 3];
    memset(grey, 128, sizeof(grey));
    write_png("grey.png", 2, 2, grey);
    s = ok_load("WorldBegin\n"
                "LightSource \"distant\" \"rgb L\" [1 1 1] \"float power\" 3\n"
                "LightSource \"infinite\" \"string filename\" \"oct.pfm\" \"rgb L\" [2 2 2]\n"
                "AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"grey.png\" \"float power\" 10\n"
                TRI "AttributeEnd\n"
                "AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"grey.png\" \"rgb L\" [2 2 2]\n"
                TRI "AttributeEnd\n", "image area lights");
    if (s) {
        const char *log = th_log_text();
        const CvLight *a = NULL;
        for (uint32_t i = 0; i < s->n_lights && !a; i++)
            if (s->lights[i].type == CV_LIGHT_AREA)
                a = &s->lights[i];
        /* grey 128 decodes to 0.2158; the triangle's area is 0.5 */
        double want = 10 / (M_PI * 0.5 * 0.21586);
        tap_ok(a && near(a->L.x, want, 2e-3 * want), "area light \"power\" over an image: by its mean "
               "luminance too (%g, want %g)", a ? a->L.x : 0, want);
        tap_ok(s->warnings == 3 && strstr(log, "main.pbrt:2:39: LightSource: parameter \"float power\" unused") &&
                   strstr(log, "infinite light with both \"L\" and \"filename\"") &&
                   strstr(log, "area light with both \"L\" and \"filename\""),
               "\"power\" on a distant light is unused; \"L\" beside \"filename\" warns (%u warnings)",
               s->warnings);
    }
    cv_scene_destroy(&s);
}

static void test_params(void)
{
    struct cv_scene *s = ok_load(
        "WorldBegin\n"
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"point2 uv\" [0 0 1 0 0 1]"
        " \"normal N\" [0 0 1 0 0 1 0 0 1] \"integer indices\" [0 1 2] \"vector3 S\" [1 0 0 1 0 0 1 0 0]\n"
        "Material \"conductor\" \"bool remaproughness\" false \"float roughness\" 0.04\n" TRI
        "Material \"conductor\" \"bool remaproughness\" \"false\" \"float roughness\" 0.04\n" TRI
        "Material \"diffuse\" \"vector2 foo\" [1 2] \"point3 bar\" [1 2 3] \"blackbody baz\" 5000\n" TRI,
        "every parameter type");
    if (s) {
        tap_ok(near(s->vertices[1].pos_u.w, 1, 1e-6) && near(s->vertices[2].nrm_v.w, 1, 1e-6), "point2 uv");
        tap_ok(near(tri_mat(s, 1)->roughness.x, 0.04, 1e-6) && near(tri_mat(s, 2)->roughness.x, 0.04, 1e-6),
               "bool unquoted and quoted");
        tap_ok(s->warnings == 4, "three unused parameters and \"S\" warned (%u)", s->warnings);
    }
    cv_scene_destroy(&s);
    s = th_load("Camera \"perspective\" \"float fov\" 45 \"float foo\" 1\nWorldBegin\n", false,
                &(struct cv_error){0});
    const char *log = th_log_text();
    tap_ok(s && strstr(log, "main.pbrt:1:37: Camera: parameter \"float foo\" unused") != NULL,
           "unused parameter warning names file:line:col: %s", log);
    cv_scene_destroy(&s);
    fails("Camera \"perspective\" \"float fov\" 45 \"float foo\" 1\nWorldBegin\n", true,
          "main.pbrt:1:37: Camera: parameter \"float foo\" unused", "--strict");
}

/* Camera motion (ActiveTransform, TransformTimes, the shutter) reaches
 * CvCamera; shapes and instances that move become moving shapes (object
 * space, after the static triangles, scene.h cv_motion); what cannot move
 * (lights, area lights, curves, shapes inside an object definition) is
 * taken at its start transform with a warning at its directive. */
static void test_motion(void)
{
    struct cv_scene *s = ok_load(
        "TransformTimes 0.25 0.75\nActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\n"
        "Camera \"perspective\" \"float shutteropen\" 0.1 \"float shutterclose\" 0.9\nWorldBegin\n" TRI,
        "a camera moving over the shutter");
    if (s) {
        const CvCamera *c = &s->camera;
        tap_ok(c->to_world[0].w == 0 && c->to_world_end[0].w == -1 && c->to_world_end[0].x == 1,
               "end transform: the camera moved to x = -1 (%g)", c->to_world_end[0].w);
        tap_ok(c->time.x == 0.1f && c->time.y == 0.9f && c->time.z == 0.25f && c->time.w == 0.75f,
               "shutter 0.1-0.9, transform times 0.25-0.75");
        tap_ok(s->warnings == 0, "a moving camera does not warn (%u)", s->warnings);
    }
    cv_scene_destroy(&s);
    s = ok_load("ActiveTransform StartTime\nTranslate 0 1 0\nActiveTransform All\nRotate 90 0 0 1\n"
                "Camera \"perspective\"\nWorldBegin\n" TRI,
                "StartTime transforms");
    if (s) {
        const CvCamera *c = &s->camera;
        /* camera to world at the start: (T(0,1,0) Rz(90))^-1 = Rz(-90)
         * T(0,-1,0), origin (-1, 0, 0); at the end Rz(-90) */
        tap_ok(near(c->to_world[0].w, -1, 1e-6) && c->to_world_end[0].w == 0 &&
                   near(c->to_world[0].y, 1, 1e-6) && near(c->to_world_end[0].y, 1, 1e-6),
               "StartTime moves the start alone; All rotates both");
        tap_ok(c->time.x == 0 && c->time.y == 1 && c->time.z == 0 && c->time.w == 1,
               "pbrt-v4's default shutter and transform times are 0 and 1");
    }
    cv_scene_destroy(&s);
    s = ok_load("ActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\nCamera \"perspective\"\n"
                "WorldBegin\nAttributeBegin\nCoordSysTransform \"camera\"\n" TRI "AttributeEnd\n" TRI,
                "a shape in the moving camera's space");
    tap_ok(s && s->warnings == 0 && s->n_motions == 1 && s->motions[0].first == 1 &&
               s->motions[0].count == 1 && s->n_triangles == 2,
           "moves with the camera: a moving shape after the static one, no warning (%u)",
           s ? s->warnings : 0);
    cv_scene_destroy(&s);
    fails("WorldBegin\nActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\n"
          "AreaLightSource \"diffuse\"\n" TRI, true,
          "main.pbrt:6:1: animated transform: moving area lights are not rendered moving", "--strict");
    fails("WorldBegin\nObjectBegin \"o\"\nActiveTransform EndTime\nTranslate 1 0 0\n"
          "ActiveTransform All\n" TRI, true,
          "main.pbrt:6:1: animated transform: shapes moving inside an object definition", "--strict");
    fails("WorldBegin\nActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\n"
          "LightSource \"point\"\n", true, "main.pbrt:5:1: animated transform: light motion blur is not "
          "rendered", "--strict");
    /* a light with its shape: the area light stays, its triangle index
     * follows the static triangles that the moving shape's move past */
    s = ok_load("WorldBegin\nAttributeBegin\nActiveTransform EndTime\nTranslate 1 0 0\n"
                "ActiveTransform All\nTranslate 0 0 5\n" TRI "AttributeEnd\n"
                "AttributeBegin\nAreaLightSource \"diffuse\"\nTranslate 0 0 7\n" TRI "AttributeEnd\n"
                "ObjectBegin \"o\"\n" TRI "ObjectEnd\n"
                "AttributeBegin\nTransformTimes 2 4\nActiveTransform StartTime\nRotate 90 0 0 1\n"
                "ActiveTransform All\nObjectInstance \"o\"\nAttributeEnd\n",
                "a moving shape before an area light, a moving instance");
    if (s) {
        tap_ok(s->warnings == 0 && s->n_motions == 2 && s->n_triangles == 3 &&
                   cv_scene_static_triangles(s) == 1 && s->motions[0].first == 1 && s->motions[1].first == 2,
               "two moving shapes after the one static triangle (%u motions)", s->n_motions);
        tap_ok(s->n_lights == 1 && s->lights[0].prim == 0 && s->tri_light[0] == 0 && s->tri_light[1] == -1 &&
                   s->tri_light[2] == -1,
               "the area light's triangle index follows its triangle (prim %u)", s ? s->lights[0].prim : 0);
        const struct cv_motion *m = &s->motions[0], *r = &s->motions[1];
        tap_ok(m->xf.moving && m->xf.t0 == 0 && m->xf.t1 == 1 && m->xf.start[2][3] == 5 &&
                   m->xf.end[0][3] == 1 && m->xf.end[2][3] == 5,
               "the shape's start and end transforms and times");
        tap_ok(near(s->vertices[s->triangles[m->first].idx.y].pos_u.x, 1, 0) &&
                   s->vertices[s->triangles[m->first].idx.y].pos_u.z == 0,
               "its vertices stay in object space");
        tap_ok(r->xf.moving && r->xf.t0 == 2 && r->xf.t1 == 4 && near(r->xf.start[0][1], -1, 1e-12) &&
                   r->xf.end[0][0] == 1,
               "the instance moves from Rotate 90 to identity over TransformTimes 2 4");
        /* the motion boxes: conservative by a little (animated.h) */
        tap_ok(s->bounds_max[0] >= 2 && s->bounds_max[0] < 2.05 && near(s->bounds_max[2], 7, 1e-3) &&
                   s->bounds_min[0] <= -1 && s->bounds_min[0] > -1.05,
               "scene bounds hold the shapes' motion (x %g..%g)", s->bounds_min[0], s->bounds_max[0]);
    }
    cv_scene_destroy(&s);
    fails("TransformTimes 1 0\n", false, "main.pbrt:1:1: TransformTimes: the start time is after", "");
    s = ok_load("Camera \"perspective\" \"float shutteropen\" 1 \"float shutterclose\" 0.5\nWorldBegin\n",
                "shutterclose before shutteropen");
    tap_ok(s && s->warnings == 1 && s->camera.time.x == 0.5f && s->camera.time.y == 1,
           "swapped, with a warning");
    cv_scene_destroy(&s);
    /* diffusetransmission's "scale" (v3 translucent's Kd) multiplies its
     * colours whether they are textured or not: a textured one gets a
     * scaled copy of its texture, or a scale node where the factor is not
     * grey or the texture inverts */
    s = ok_load("WorldBegin\n"
                "Texture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\"\n"
                "Texture \"inv\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\" \"bool invert\" true\n"
                "MakeNamedMaterial \"a\" \"string type\" \"diffusetransmission\" \"texture reflectance\" \"img\""
                " \"rgb transmittance\" [0.4 0.4 0.4] \"float scale\" 2\n"
                "MakeNamedMaterial \"b\" \"string type\" \"diffusetransmission\" \"texture transmittance\" \"inv\""
                " \"float scale\" 0.5\n"
                "MakeNamedMaterial \"c\" \"string type\" \"translucent\" \"texture reflect\" \"img\""
                " \"rgb Kd\" [0.5 0.25 1]\n"
                "NamedMaterial \"a\"\n" TRI,
                "diffusetransmission scale with textures");
    if (s) {
        const CvMaterial *m = s->materials;
        const CvTexture *t = s->textures;
        int ia = m[0].reflectance_tex, ib = m[1].specular_tex, ic = m[2].reflectance_tex;
        tap_ok(ia >= 0 && t[ia].type == CV_TEX_IMAGE && near(t[ia].scale, 2, 1e-6) &&
               near(m[0].specular.x, 0.8, 1e-6), "scale 2 on a textured reflectance: its copy scaled (%g), "
               "the constant transmittance too", ia >= 0 ? t[ia].scale : 0);
        int img = -1;
        for (uint32_t i = 0; i < s->n_textures; i++)
            if (t[i].type == CV_TEX_IMAGE && near(t[i].scale, 1, 0) && !(t[i].flags & CV_TEXF_INVERT))
                img = (int)i;
        tap_ok(img >= 0 && img != ia, "the named texture itself keeps its scale");
        tap_ok(ib >= 0 && t[ib].type == CV_TEX_SCALE && near(t[ib].value_b.x, 0.5, 1e-6) && t[ib].tex_a >= 0 &&
                   (t[t[ib].tex_a].flags & CV_TEXF_INVERT),
               "scale 0.5 on an inverted texture: a scale node over it");
        tap_ok(ic >= 0 && t[ic].type == CV_TEX_SCALE && near(t[ic].value_b.x, 0.5, 1e-6) &&
                   near(t[ic].value_b.y, 0.25, 1e-6) && near(t[ic].value_b.z, 1, 1e-6),
               "translucent's Kd on a textured reflect: a scale node by Kd");
    }
    cv_scene_destroy(&s);
    /* a float texture reads the alpha of an RGBA PNG whose alpha is not
     * all 1, as pbrt-v4 does; an opaque RGBA PNG and an RGB one do not */
    unsigned char rgba[2 * 2 * 4] = {255, 255, 255, 0, 255, 255, 255, 255,
                                     255, 255, 255, 128, 255, 255, 255, 255};
    write_png_as("a.png", 2, 2, rgba, true);
    for (int i = 0; i < 4; i++)
        rgba[4 * i + 3] = 255;
    write_png_as("o.png", 2, 2, rgba, true);
    s = ok_load("WorldBegin\n"
                "Texture \"a\" \"float\" \"imagemap\" \"string filename\" \"a.png\"\n"
                "Texture \"o\" \"float\" \"imagemap\" \"string filename\" \"o.png\"\n"
                "Texture \"r\" \"float\" \"imagemap\" \"string filename\" \"t.png\"\n"
                "Material \"diffuse\"\n" TRI, "float textures of RGBA PNGs");
    if (s) {
        /* the float textures a, o, r in the order they were defined */
        const CvTexture *t[3] = {NULL, NULL, NULL};
        for (uint32_t i = 0, k = 0; i < s->n_textures && k < 3; i++)
            if (s->textures[i].flags & CV_TEXF_FLOAT)
                t[k++] = &s->textures[i];
        float a[4] = {0};
        if (t[0])
            cv_scene_texel(s, t[0], 2, a);
        /* the float texture reads the average of r, g, b (texture.glsl):
         * for the RGBA PNG a copy holds the alpha there, the others keep
         * their colour (white) */
        float o[4] = {0}, r[4] = {0};
        if (t[2]) {
            cv_scene_texel(s, t[1], 2, o);
            cv_scene_texel(s, t[2], 0, r);
        }
        tap_ok(t[2] && near(a[0], 0.2158, 2e-3) && a[0] == a[1] && a[1] == a[2] && near(o[0], 1, 1e-3) &&
                   near(r[0], 1, 1e-3),
               "the RGBA PNG with a transparent texel reads its alpha (%g %g %g); the opaque one (%g) and the RGB one "
               "(%g) their colour", a[0], a[1], a[2], o[0], r[0]);
        tap_ok(near(a[3], 0.2158, 2e-3), "its alpha is decoded from sRGB as its colour, as pbrt-v4 does (%g)", a[3]);
        bool marked = false;
        for (uint32_t i = 0; i < s->n_textures; i++)
            marked = marked || (s->textures[i].type == CV_TEX_IMAGE && !(s->textures[i].flags & CV_TEXF_FLOAT) &&
                                (s->textures[i].flags & CV_TEXF_ALPHA) && s->textures[i].width == 2);
        tap_ok(marked, "the loader marks the image itself (CV_TEXF_ALPHA)");
    }
    cv_scene_destroy(&s);
    /* composites nest two deep on the GPU: a third level warns */
    s = ok_load("WorldBegin\n"
                "Texture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\"\n"
                "Texture \"s1\" \"spectrum\" \"scale\" \"texture tex\" \"img\" \"float scale\" 0.5\n"
                "Texture \"s2\" \"spectrum\" \"mix\" \"texture tex1\" \"s1\" \"rgb tex2\" [0 0 1]\n"
                "Texture \"s3\" \"spectrum\" \"scale\" \"texture tex\" \"s2\" \"float scale\" 2\n"
                "Material \"diffuse\" \"texture reflectance\" \"s3\"\n" TRI,
                "composite textures three deep");
    if (s)
        tap_ok(s->warnings == 1 && strstr(th_log_text(), "main.pbrt:5:1: texture \"s3\" nests composite textures 3 deep"),
               "a third level of composites warns at its texture (%u)", s->warnings);
    cv_scene_destroy(&s);
    /* pbrt-v4 reads a TGA through stb_image as sRGB whatever the encoding
     * (Image::Read): so does Cavalry, with a warning */
    s = ok_load("WorldBegin\n"
                "Texture \"lin\" \"spectrum\" \"imagemap\" \"string filename\" \"t.tga\" \"string encoding\" \"linear\"\n"
                "Material \"diffuse\" \"texture reflectance\" \"lin\"\n" TRI,
                "encoding linear of a TGA");
    if (s) {
        const CvTexture *t = &s->textures[tri_mat(s, 0)->reflectance_tex];
        uint32_t g = s->texels[2 * (t->offset + 2)];
        tap_ok((t->flags & CV_TEXF_SRGB) && near(cv_half_to_float((uint16_t)(g & 0xffff)), 0.2158, 2e-3) &&
               s->warnings == 1, "encoding linear of a TGA: decoded from sRGB, as pbrt-v4 does, with a warning (%u)",
               s->warnings);
    }
    cv_scene_destroy(&s);
}

static void test_more(void)
{
    unsigned char px[2 * 2 * 3] = {128, 128, 255, 128, 128, 255, 128, 128, 255, 128, 128, 255};
    write_tga("n.tga", 2, 2, px);
    write_png("n.png", 2, 2, px);
    struct cv_scene *s = ok_load(
        "WorldBegin\nTransformTimes 0 1\nActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\n"
        "Texture \"r\" \"float\" \"imagemap\" \"string filename\" \"n.tga\"\n"
        "Material \"conductor\" \"texture roughness\" \"r\" \"string normalmap\" \"n.png\"\n"
        "MakeNamedMaterial \"x\" \"string type\" \"diffuse\"\nMakeNamedMaterial \"x\" \"string type\" \"diffuse\"\n"
        "LightSource \"point\" \"blackbody I\" [ 6500 2 ]\n" TRI,
        "ActiveTransform, TransformTimes, roughness texture, normal map, v3 blackbody");
    if (s) {
        const CvMaterial *m = tri_mat(s, 0);
        tap_ok(m->roughness_u_tex >= 0 && m->roughness_v_tex == m->roughness_u_tex &&
               (m->flags & CV_MATF_REMAP_ROUGHNESS) && !(m->flags & CV_MATF_ROUGHNESS_V3),
               "textured roughness is remapped per lookup, as pbrt-v4 remaps");
        tap_ok(m->normal_tex >= 0 && !(s->textures[m->normal_tex].flags & CV_TEXF_SRGB), "PNG normal map is linear");
        tap_ok(s->warnings == 2, "the moving light and the redefined material warn (%u)", s->warnings);
        tap_ok(near(lum(s->lights[0].L), 2, 2e-3), "v3 blackbody [T scale]");
        tap_ok(vpos(s, 0, 0, 0, 0) && s->n_motions == 1, "the shape moves, in object space");
    }
    cv_scene_destroy(&s);
    /* pbrt-v4 drops the area light of an "interface" shape, with a warning */
    s = ok_load("WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
                "Material \"interface\"\n" TRI "AttributeEnd\n"
                "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n" TRI, "area lights on interface and diffuse");
    if (s)
        tap_ok(s->n_lights == 1 && s->warnings == 1 && strstr(th_log_text(), "main.pbrt:5:1: the area light of a shape"),
               "the interface shape's area light is dropped with a warning at its shape (%u lights, %u warnings)",
               s->n_lights, s->warnings);
    cv_scene_destroy(&s);
    /* a cut-out emitter: its light is marked to be masked by the alpha, as
     * pbrt-v4 masks it (tests/trace/alpha_emitter_test.c renders it) */
    s = ok_load("WorldBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
                "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2] \"float alpha\" 0.5\n"
                TRI, "cut-out emitter");
    if (s)
        tap_ok(s->n_lights == 2 && s->warnings == 0 && (s->lights[0].flags & CV_LIGHTF_ALPHA) &&
                   !(s->lights[1].flags & CV_LIGHTF_ALPHA),
               "a cut-out emitter's light is marked as cut out, a whole one's not (%u warnings)",
               s->warnings);
    cv_scene_destroy(&s);
    /* pbrt-v3 materials remap a textured roughness by pbrt-v3's polynomial */
    s = ok_load("WorldBegin\nTexture \"r\" \"float\" \"constant\" \"float value\" 0.1\n"
                "Material \"metal\" \"texture roughness\" \"r\"\n" TRI
                "Material \"glass\" \"texture uroughness\" \"r\"\n" TRI
                "Material \"substrate\" \"texture vroughness\" \"r\"\n" TRI
                "Material \"metal\" \"texture roughness\" \"r\" \"bool remaproughness\" false\n" TRI,
                "pbrt-v3 textured roughness");
    if (s) {
        bool v3 = true;
        for (int i = 0; i < 3; i++)
            v3 = v3 && (tri_mat(s, (uint32_t)i)->flags & (CV_MATF_REMAP_ROUGHNESS | CV_MATF_ROUGHNESS_V3)) ==
                           (CV_MATF_REMAP_ROUGHNESS | CV_MATF_ROUGHNESS_V3);
        tap_ok(v3, "metal, glass and substrate remap a textured roughness as pbrt-v3 does");
        tap_ok(!(tri_mat(s, 3)->flags & (CV_MATF_REMAP_ROUGHNESS | CV_MATF_ROUGHNESS_V3)),
               "... and not with remaproughness false");
    }
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nMaterial \"diffuse\" \"string normalmap\" \"n.tga\"\n" TRI, "TGA normal map");
    if (s) {
        const CvMaterial *m = tri_mat(s, 0);
        tap_ok(m->normal_tex >= 0 && (s->textures[m->normal_tex].flags & CV_TEXF_SRGB) && s->warnings == 1,
               "TGA normal map: decoded from sRGB, as pbrt-v4 does, with a warning (%u)", s->warnings);
    }
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nAttributeBegin\nAttribute \"shape\" \"float radius\" 3\n"
                "Attribute \"material\" \"rgb reflectance\" [0.1 0.1 0.1]\nMaterial \"diffuse\"\n"
                "Shape \"sphere\"\nShape \"sphere\" \"float radius\" 1\nAttributeEnd\nShape \"sphere\"\n",
                "Attribute defaults");
    if (s) {
        bool r3 = false, after = true;
        uint32_t per = s->n_triangles / 3;
        for (uint32_t v = 0; v < s->n_vertices; v++)
            r3 = r3 || near(s->vertices[v].pos_u.z, 3, 1e-5);
        for (uint32_t t = 2 * per; t < s->n_triangles; t++)
            for (int k = 0; k < 3; k++) {
                uint32_t v = (&s->triangles[t].idx.x)[k];
                after = after && fabs(s->vertices[v].pos_u.z) <= 1 + 1e-5;
            }
        tap_ok(r3 && after && s->warnings == 0, "Attribute \"shape\" radius applies inside its scope only");
        tap_ok(near(tri_mat(s, 0)->reflectance.x, 0.1, 1e-6), "Attribute \"material\" default");
    }
    cv_scene_destroy(&s);
    s = ok_load("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]"
                " \"vector3 S\" [1 0 0 1 0 0 1 0 0]\n" TRI, "trianglemesh with \"S\"");
    if (s)
        tap_ok(s->warnings == 1 && strstr(th_log_text(), "main.pbrt:2:79: \"S\" (shading tangents) is not rendered"),
               "\"S\" warns at its place (%u)", s->warnings);
    cv_scene_destroy(&s);
    fails("WorldBegin\nShape \"loopsubdiv\" \"integer levels\" 30 \"point3 P\" [0 0 0 1 0 0 0 1 0]"
          " \"integer indices\" [0 1 2]\n", false, "main.pbrt:2:1: loopsubdiv with 30 levels", "loopsubdiv bounded");
}

static void test_include(void)
{
    mkdir(th_path("sub"), 0755);
    th_write_str("sub/inc.pbrt", "Include \"geo.pbrt\"\n");
    th_write_str("sub/geo.pbrt", TRI);
    struct cv_scene *s = ok_load("WorldBegin\nInclude \"sub/inc.pbrt\"\nImport \"sub/geo.pbrt\"\n", "Include/Import");
    tap_ok(s && s->n_triangles == 2, "includes resolve relative to the including file");
    cv_scene_destroy(&s);
    th_write_str("sub/nested.pbrt", "Shape \"plymesh\" \"string filename\" \"quad.ply\"\n");
    s = ok_load("WorldBegin\nInclude \"sub/nested.pbrt\"\n", "file named in an include, found from the main folder");
    tap_ok(s && s->n_triangles == 2, "pbrt-style fallback to the top-level folder");
    cv_scene_destroy(&s);
    th_write_str("a.pbrt", "Include \"b.pbrt\"\n");
    th_write_str("b.pbrt", "\n  Include \"a.pbrt\"\n");
    fails("WorldBegin\nInclude \"a.pbrt\"\n", false, "b.pbrt:2:3: recursive include of \"a.pbrt\"", "recursive include");
    fails("WorldBegin\nInclude \"nothere.pbrt\"\n", false, "main.pbrt:2:1: cannot include \"nothere.pbrt\"",
          "missing include");
    fails("WorldBegin\nShape \"plymesh\" \"string filename\" \"none.ply\"\n", false, "main.pbrt:2:1: plymesh \"none.ply\"",
          "missing ply");
    th_write_str("bad.pbrt", "Translate 1 2\n");
    fails("Include \"bad.pbrt\"\n", false, "bad.pbrt:2:1: Translate expects 3 numbers", "error inside an include");
}

static void test_errors(void)
{
    fails("Translate 1 2x 3\n", false, "main.pbrt:1:13: bad number \"2x\"", "bad number");
    fails("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0", false, "main.pbrt:2:40: unbalanced '['",
          "truncated file inside brackets");
    fails("WorldBegin\nShape \"trianglem", false, "main.pbrt:2:7: unterminated string", "truncated string");
    fails("WorldBegin\nShape \"sphere\" \"float radius\" [ 1\nWorldEnd\n", false,
          "main.pbrt:3:1: unexpected \"WorldEnd\"", "unbalanced brackets");
    fails("Translate 1 2 3 ]\n", false, "main.pbrt:1:17: expected a directive", "stray ]");
    fails("WorldBegin\nAttributeEnd\n", false, "main.pbrt:2:1: AttributeEnd without a matching AttributeBegin",
          "AttributeEnd without begin");
    fails("WorldBegin\n  AttributeBegin\n", false, "main.pbrt:2:3: AttributeBegin not closed", "AttributeBegin unclosed");
    fails("WorldBegin\nFrobnicate 3\n", false, "main.pbrt:2:1: unknown directive \"Frobnicate\"",
          "unknown directive");
    fails("Frobnicate 3\n", false, "main.pbrt:1:1: not a pbrt scene file", "unknown first word");
    fails("root:x:0:0:root:/root:/bin/bash\n", false, "main.pbrt:1:1: not a pbrt scene file (it does "
          "not start with a directive)", "a file that is no scene");
    fails("WorldBegin\nNamedMaterial \"x\"\n", false, "main.pbrt:2:1: unknown named material \"x\"", "unknown material");
    fails("WorldBegin\nMaterial \"diffuse\" \"texture reflectance\" \"nope\"\n", false,
          "main.pbrt:2:20: unknown texture \"nope\"", "unknown texture");
    fails("WorldBegin\nShape \"sphere\" \"flot radius\" 1\n", true, "main.pbrt:2:16: unknown parameter type \"flot\"",
          "unknown parameter type (--strict)");
    struct cv_error e2 = {0};
    struct cv_scene *s = th_load("WorldBegin\nShape \"sphere\" \"flot radius\" [ 1 ] \"float zmin\" 0\n", false, &e2);
    tap_ok(s && s->warnings == 1 && strstr(th_log_text(), "main.pbrt:2:16: unknown parameter type \"flot\""),
           "unknown parameter type is a warning with location");
    cv_scene_destroy(&s);
    fails("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 5]\n", false,
          "index 5 out of range", "index out of range");
    fails("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1]\n", false, "main.pbrt:2:22: parameter \"point3 P\" has 4 values",
          "wrong value count");
    fails("WorldBegin\nMaterial \"diffuse\" \"bool x\" 3\n", false, "main.pbrt:2:29: bool parameter", "bool from a number");
    fails("WorldBegin\nScale 1e300 1 1\nScale 1e300 1 1\n" TRI, false, "main.pbrt:4:1: vertex positions are not finite",
          "overflowing transform");
    fails("WorldBegin\nObjectInstance \"none\"\n", false, "main.pbrt:2:1: unknown object", "unknown object");
    fails("WorldBegin\nMaterial \"conductor\" \"spectrum eta\" \"no-such.spd\"\n", false,
          "main.pbrt:2:22: spectrum \"no-such.spd\" is neither a known name nor a readable file", "bad spectrum");
}

int main(void)
{
    th_init();
    test_transforms();
    test_grid_media();
    test_medium_presets();
    test_cloud_media();
    test_attributes();
    test_settings();
    test_shapes();
    test_materials();
    test_hair_material();
    test_textures();
    test_lights();
    test_params();
    test_more();
    test_motion();
    test_include();
    test_errors();
    th_cleanup();
    return tap_done();
}
