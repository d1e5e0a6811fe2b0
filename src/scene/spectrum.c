/* spectrum.c: colours and spectra to linear Rec.709 RGB. Spectra are
 * integrated against the CIE 1931 matching functions given by the
 * multi-lobe Gaussian fit of Wyman, Sloan and Shirley (JCGT 2013), which is
 * within a few percent of the tables and needs no data. Named metal spectra
 * are stored as their RGB conversions (eta, k), named glasses as their index
 * at 550 nm: the renderer is RGB, so that is all that survives anyway. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/builder.h"
#include "scene/spectrum.h"

static double lobe(double l, double mu, double s1, double s2)
{
    double t = (l - mu) / (l < mu ? s1 : s2);
    return exp(-0.5 * t * t);
}

static void cie_xyz(double l, double xyz[3])
{
    xyz[0] = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
             0.065 * lobe(l, 501.1, 20.4, 26.2);
    xyz[1] = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
    xyz[2] = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
}

static void xyz_to_rgb(const double xyz[3], double rgb[3])
{
    rgb[0] = 3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2];
    rgb[1] = -0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2];
    rgb[2] = 0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2];
}

/* Piecewise-linear spectrum from sorted (lambda, value) pairs; beyond
 * them the end values (clamp) or 0 (pbrt-v4's PiecewiseLinearSpectrum). */
static double eval_pairs_outside(const double *pairs, size_t n, double l, bool clamp)
{
    if (n == 0)
        return 0;
    if (n == 1)
        return pairs[1];
    if (l < pairs[0] || l > pairs[2 * (n - 1)])
        return clamp ? pairs[l < pairs[0] ? 1 : 2 * (n - 1) + 1] : 0;
    size_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (pairs[2 * mid] <= l)
            lo = mid;
        else
            hi = mid;
    }
    double l0 = pairs[2 * lo], l1 = pairs[2 * hi];
    double t = l1 > l0 ? (l - l0) / (l1 - l0) : 0;
    return pairs[2 * lo + 1] * (1 - t) + pairs[2 * hi + 1] * t;
}

static double eval_pairs(const double *pairs, size_t n, double l)
{
    return eval_pairs_outside(pairs, n, l, true);
}

double cv_spectrum_at(const double *pairs, size_t n, double lambda)
{
    return eval_pairs_outside(pairs, n, lambda, false);
}

static double planck(double l_nm, double T)
{
    const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    double l = l_nm * 1e-9;
    return (2 * h * c * c) / (pow(l, 5) * (exp((h * c) / (l * kb * T)) - 1));
}

/* Integrates spectrum f (pairs, or blackbody when T > 0, an emission) to
 * RGB. An emission goes to XYZ as it is (an equal-energy spectrum is
 * pinkish against sRGB's white, in pbrt-v4 too), at luminance 1; a
 * reflectance or other factor is seen under the colour space's white, D65,
 * as pbrt-v4 renders it under an RGB light, so that a constant spectrum
 * keeps its value in each channel (cv_spectrum_rgb_weights_nm). */
static void spectrum_rgb(const double *pairs, size_t n, double T, enum cv_spectrum_kind kind,
                         double rgb[3])
{
    if (kind != CV_SPEC_ILLUMINANT) {
        double w[3 * CV_SPECTRUM_NM];
        cv_spectrum_rgb_weights_nm(w);
        rgb[0] = rgb[1] = rgb[2] = 0;
        for (int i = 0; i < CV_SPECTRUM_NM; i++) {
            double v = eval_pairs(pairs, n, CV_SPECTRUM_NM_MIN + i);
            for (int c = 0; c < 3; c++)
                rgb[c] += v * w[3 * i + c];
        }
        return;
    }
    double xyz[3] = {0, 0, 0};
    for (double l = 360; l <= 830; l += 1) {
        double m[3], v = T > 0 ? planck(l, T) : eval_pairs(pairs, n, l);
        cie_xyz(l, m);
        for (int c = 0; c < 3; c++)
            xyz[c] += v * m[c];
    }
    double y = xyz[1];
    if (!(fabs(y) > 0)) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    for (int c = 0; c < 3; c++)
        xyz[c] /= y;
    xyz_to_rgb(xyz, rgb);
}

/* CIE standard illuminant D65, 360..830 nm in steps of 10 nm. */
static const double d65[] = {
    46.6383, 52.0891, 49.9755, 54.6482, 82.7549, 91.486,  93.4318, 86.6823, 104.865, 117.008,
    117.812, 114.861, 115.923, 108.811, 109.354, 107.802, 104.79,  107.689, 104.405, 104.046,
    100.0,   96.3342, 95.788,  88.6856, 90.0062, 89.5991, 87.6987, 83.2886, 83.6992, 80.0268,
    80.2146, 82.2778, 78.2842, 69.7213, 71.6091, 74.349,  61.604,  69.8856, 75.087,  63.5927,
    46.4182, 66.8054, 63.3828, 64.304,  59.4519, 51.959,  57.4406, 60.3125,
};

static double d65_at(double l)
{
    double x = (l - 360) / 10;
    int i = (int)x;
    if (i < 0)
        return d65[0];
    if (i >= (int)CV_ARRAY_SIZE(d65) - 1)
        return d65[CV_ARRAY_SIZE(d65) - 1];
    return d65[i] + (x - i) * (d65[i + 1] - d65[i]);
}

void cv_spectrum_rgb_weights_nm(double *w)
{
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < CV_SPECTRUM_NM; i++) {
        double l = CV_SPECTRUM_NM_MIN + i, xyz[3], rgb[3], e = d65_at(l);
        cie_xyz(l, xyz);
        xyz_to_rgb(xyz, rgb);
        for (int c = 0; c < 3; c++) {
            w[3 * i + c] = e * rgb[c];
            sum[c] += e * rgb[c];
        }
    }
    for (int i = 0; i < CV_SPECTRUM_NM; i++)
        for (int c = 0; c < 3; c++)
            w[3 * i + c] /= sum[c];
}

void cv_spectrum_rgb_weights(const float *lambda, size_t n, double *w)
{
    double nm[3 * CV_SPECTRUM_NM];
    cv_spectrum_rgb_weights_nm(nm);
    for (size_t k = 0; k < 3 * n; k++)
        w[k] = 0;
    for (int i = 0; i < CV_SPECTRUM_NM; i++) {
        double l = CV_SPECTRUM_NM_MIN + i;
        const double *rgb = nm + 3 * i;
        /* the hat functions of the nodes around l */
        size_t k = 0;
        while (k + 1 < n && lambda[k + 1] <= l)
            k++;
        double t = 0;
        if (k + 1 < n && l > lambda[k])
            t = (l - lambda[k]) / (lambda[k + 1] - lambda[k]);
        for (int c = 0; c < 3; c++) {
            w[3 * k + c] += (1 - t) * rgb[c];
            if (t > 0)
                w[3 * (k + 1) + c] += t * rgb[c];
        }
    }
}

static const struct {
    const char *name;
    double rgb[3];
} named_rgb[] = {
    {"metal-Ag-eta", {0.155265, 0.116723, 0.138342}},
    {"metal-Ag-k", {4.82835, 3.12225, 2.14696}},
    {"metal-Al-eta", {1.65746, 0.880369, 0.521229}},
    {"metal-Al-k", {9.22387, 6.26952, 4.837}},
    {"metal-Au-eta", {0.143119, 0.374957, 1.44248}},
    {"metal-Au-k", {3.98316, 2.38572, 1.60322}},
    {"metal-Cu-eta", {0.200438, 0.924033, 1.10221}},
    {"metal-Cu-k", {3.91295, 2.45285, 2.14219}},
    {"metal-CuZn-eta", {0.444, 0.527, 1.094}},
    {"metal-CuZn-k", {3.695, 2.765, 1.829}},
    {"metal-MgO-eta", {1.732, 1.738, 1.760}},
    {"metal-MgO-k", {0, 0, 0}},
    {"metal-TiO2-eta", {2.58, 2.67, 2.87}},
    {"metal-TiO2-k", {0, 0, 0}},
    {"glass-BK7", {1.5185, 1.5185, 1.5185}},
    {"glass-BAF10", {1.6732, 1.6732, 1.6732}},
    {"glass-FK51A", {1.4879, 1.4879, 1.4879}},
    {"glass-LASF9", {1.8559, 1.8559, 1.8559}},
    {"glass-F5", {1.6777, 1.6777, 1.6777}},
    {"glass-F10", {1.7358, 1.7358, 1.7358}},
    {"glass-F11", {1.7919, 1.7919, 1.7919}},
    {"stdillum-D65", {1, 1, 1}},
    {"illum-acesD60", {1, 1, 1}},
};

/* Reads a .spd file: "lambda value" pairs, # comments. */
static bool read_spd(const char *path, double **pairs, size_t *n, struct cv_error *err)
{
    char *data;
    size_t len;
    if (!cv_read_file(path, &data, &len, err))
        return false;
    size_t cap = 0, count = 0;
    double *v = NULL;
    char *s = data;
    while (*s) {
        if (*s == '#') {
            while (*s && *s != '\n')
                s++;
            continue;
        }
        if (isspace((unsigned char)*s) || *s == ',') {
            s++;
            continue;
        }
        char *end;
        double x = strtod(s, &end);
        if (end == s || !isfinite(x)) {
            free(v);
            free(data);
            return cv_fail(err, "%s: not a number in the spectrum file", path);
        }
        CV_PUSH(v, count, cap, x);
        s = end;
    }
    free(data);
    if (count < 2 || count % 2) {
        free(v);
        return cv_fail(err, "%s: a spectrum file needs (wavelength, value) pairs", path);
    }
    *pairs = v;
    *n = count / 2;
    return true;
}

static bool sorted_pairs(const double *p, size_t n)
{
    for (size_t i = 1; i < n; i++)
        if (!(p[2 * i] > p[2 * (i - 1)]))
            return false;
    return true;
}

bool cv_b_color(struct cv_builder *b, struct cv_params *ps, const char *name,
                enum cv_spectrum_kind kind, const char *dir, double rgb[3], bool *found,
                struct cv_error *err)
{
    *found = false;
    struct cv_param *p = NULL;
    for (size_t i = ps->n; i-- > 0;)
        if (strcmp(ps->v[i].name, name) == 0 && ps->v[i].type != CV_PARAM_TEXTURE) {
            p = &ps->v[i];
            break;
        }
    if (!p)
        return true;
    p->used = true;
    struct cv_loc loc = {p->file, p->line, p->col};
    switch (p->type) {
    case CV_PARAM_RGB:
        if (p->n_nums != 3)
            return cv_fail(err, "%s:%d:%d: \"%s\" needs 3 values", p->file, p->line, p->col, name);
        for (int c = 0; c < 3; c++)
            rgb[c] = p->nums[c];
        break;
    case CV_PARAM_FLOAT:
        rgb[0] = rgb[1] = rgb[2] = p->nums[0];
        break;
    case CV_PARAM_BLACKBODY: {
        double T = p->nums[0];
        if (!(T > 0))
            return cv_fail(err, "%s:%d:%d: blackbody temperature must be positive", p->file,
                           p->line, p->col);
        spectrum_rgb(NULL, 0, T, CV_SPEC_ILLUMINANT, rgb);
        if (p->n_nums >= 2) /* v3: [T scale] */
            for (int c = 0; c < 3; c++)
                rgb[c] *= p->nums[1];
        break;
    }
    case CV_PARAM_SPECTRUM:
        if (p->n_strs) {
            const char *s = p->strs[0];
            size_t i;
            for (i = 0; i < CV_ARRAY_SIZE(named_rgb); i++)
                if (strcmp(named_rgb[i].name, s) == 0)
                    break;
            if (i < CV_ARRAY_SIZE(named_rgb)) {
                memcpy(rgb, named_rgb[i].rgb, sizeof(double) * 3);
                break;
            }
            if (strcmp(s, "stdillum-A") == 0) {
                spectrum_rgb(NULL, 0, 2856, CV_SPEC_ILLUMINANT, rgb);
                break;
            }
            if (strncmp(s, "stdillum-", 9) == 0 || strncmp(s, "illum-", 6) == 0) {
                if (!cv_b_warn(b, err, &loc, "named spectrum \"%s\" read as white", s))
                    return false;
                rgb[0] = rgb[1] = rgb[2] = 1;
                break;
            }
            char *path = cv_b_resolve(b, dir, s, err);
            double *pairs = NULL;
            size_t n = 0;
            if (!path || !read_spd(path, &pairs, &n, err)) {
                free(path);
                cv_error_prefix(err, "%s:%d:%d: spectrum \"%s\" is neither a known name nor a readable file",
                                p->file, p->line, p->col, s);
                return false;
            }
            free(path);
            if (!sorted_pairs(pairs, n)) {
                free(pairs);
                return cv_fail(err, "%s:%d:%d: spectrum file \"%s\": wavelengths must increase",
                               p->file, p->line, p->col, s);
            }
            spectrum_rgb(pairs, n, 0, kind, rgb);
            free(pairs);
        } else {
            if (!sorted_pairs(p->nums, p->n_nums / 2))
                return cv_fail(err, "%s:%d:%d: spectrum \"%s\": wavelengths must increase",
                               p->file, p->line, p->col, name);
            spectrum_rgb(p->nums, p->n_nums / 2, 0, kind, rgb);
        }
        break;
    default:
        return cv_fail(err, "%s:%d:%d: \"%s\" must be a colour (rgb, spectrum, blackbody), not %s",
                       p->file, p->line, p->col, name, cv_param_type_name(p->type));
    }
    for (int c = 0; c < 3; c++)
        if (!isfinite(rgb[c]))
            return cv_fail(err, "%s:%d:%d: \"%s\" is not finite", p->file, p->line, p->col, name);
    *found = true;
    return true;
}

bool cv_b_spectrum(struct cv_builder *b, struct cv_params *ps, const char *name,
                   const char *dir, double **pairs, size_t *n, struct cv_error *err)
{
    *pairs = NULL;
    *n = 0;
    struct cv_param *p = NULL;
    for (size_t i = ps->n; i-- > 0;)
        if (strcmp(ps->v[i].name, name) == 0) {
            p = &ps->v[i];
            break;
        }
    if (!p)
        return true;
    if ((p->type == CV_PARAM_FLOAT && p->n_nums >= 1) ||
        (p->type == CV_PARAM_SPECTRUM && !p->n_strs && p->n_nums >= 2 && p->n_nums % 2 == 0 &&
         sorted_pairs(p->nums, p->n_nums / 2))) {
        bool constant = p->type == CV_PARAM_FLOAT;
        *n = constant ? 1 : p->n_nums / 2;
        *pairs = cv_xmalloc(2 * *n * sizeof(double));
        if (constant) {
            (*pairs)[0] = 550;
            (*pairs)[1] = p->nums[0];
        } else {
            memcpy(*pairs, p->nums, 2 * *n * sizeof(double));
        }
        return true;
    }
    if (p->type != CV_PARAM_SPECTRUM || !p->n_strs)
        return true;
    const char *s = p->strs[0];
    size_t count;
    const double *metal = cv_metal_spectrum(s, &count);
    if (metal) {
        *pairs = cv_xmalloc(2 * count * sizeof(double));
        memcpy(*pairs, metal, 2 * count * sizeof(double));
        *n = count;
        return true;
    }
    for (size_t i = 0; i < CV_ARRAY_SIZE(named_rgb); i++)
        if (strcmp(named_rgb[i].name, s) == 0)
            return true;
    if (strncmp(s, "stdillum-", 9) == 0 || strncmp(s, "illum-", 6) == 0)
        return true;
    char *path = cv_b_resolve(b, dir, s, err);
    if (!path)
        return false;
    bool ok = read_spd(path, pairs, n, err);
    free(path);
    if (ok && !sorted_pairs(*pairs, *n)) {
        free(*pairs);
        *pairs = NULL;
        *n = 0; /* cv_b_color reports it */
    }
    return ok;
}

bool cv_b_scalar_eta(struct cv_builder *b, struct cv_params *ps, const char *name,
                     const char *dir, double *eta, bool *found, struct cv_error *err)
{
    /* A spectrally varying eta would need spectral dispersion, which an
     * RGB renderer has not: one value stands for all (550 nm, green), and
     * a warning says so. */
    struct cv_param *p = NULL;
    *found = false;
    for (size_t i = ps->n; i-- > 0;)
        if (strcmp(ps->v[i].name, name) == 0 && ps->v[i].type != CV_PARAM_TEXTURE) {
            p = &ps->v[i];
            break;
        }
    if (!p)
        return true;
    /* the least and most of the index over the visible range, or of its
     * RGB, to tell a varying one */
    double lo, hi;
    if (p->type == CV_PARAM_SPECTRUM && p->n_strs == 0) {
        p->used = true;
        size_t n = p->n_nums / 2;
        if (!sorted_pairs(p->nums, n))
            return cv_fail(err, "%s:%d:%d: spectrum \"%s\": wavelengths must increase",
                           p->file, p->line, p->col, name);
        *eta = eval_pairs(p->nums, n, 550);
        *found = true;
        lo = hi = *eta;
        for (double l = 400; l <= 700; l += 10) {
            double v = eval_pairs(p->nums, n, l);
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
    } else {
        double rgb[3];
        if (!cv_b_color(b, ps, name, CV_SPEC_UNBOUNDED, dir, rgb, found, err))
            return false;
        if (!*found)
            return true;
        *eta = p->type == CV_PARAM_RGB ? rgb[1] : (rgb[0] + rgb[1] + rgb[2]) / 3;
        lo = fmin(rgb[0], fmin(rgb[1], rgb[2]));
        hi = fmax(rgb[0], fmax(rgb[1], rgb[2]));
        /* pbrt-v4's named glasses are dispersion curves; the table here
         * holds their value at 550 nm alone */
        if (p->type == CV_PARAM_SPECTRUM && p->n_strs && strncmp(p->strs[0], "glass-", 6) == 0)
            hi = INFINITY;
    }
    if (hi - lo > 1e-3 * fabs(*eta)) {
        const struct cv_loc at = {p->file, p->line, p->col};
        return cv_b_warn(b, err, &at, "\"%s\" varies with wavelength: pbrt-v4 refracts each "
                         "wavelength by its own index (dispersion); one index, %.4g, is rendered",
                         name, *eta);
    }
    return true;
}

bool cv_b_color_tex(struct cv_builder *b, struct cv_params *ps, const char *name,
                    enum cv_spectrum_kind kind, const char *dir, double rgb[3], int *tex,
                    struct cv_error *err)
{
    *tex = -1;
    for (size_t i = ps->n; i-- > 0;) {
        struct cv_param *p = &ps->v[i];
        if (strcmp(p->name, name) != 0)
            continue;
        if (p->type != CV_PARAM_TEXTURE)
            break;
        p->used = true;
        int t = cv_b_lookup(b->spec_tex, b->n_spec_tex, p->strs[0]);
        if (t < 0)
            t = cv_b_lookup(b->float_tex, b->n_float_tex, p->strs[0]);
        if (t < 0)
            return cv_fail(err, "%s:%d:%d: unknown texture \"%s\"", p->file, p->line, p->col,
                           p->strs[0]);
        *tex = t;
        return true;
    }
    bool found;
    return cv_b_color(b, ps, name, kind, dir, rgb, &found, err);
}

bool cv_b_float_tex(struct cv_builder *b, struct cv_params *ps, const char *name,
                    double *val, int *tex, struct cv_error *err)
{
    *tex = -1;
    for (size_t i = ps->n; i-- > 0;) {
        struct cv_param *p = &ps->v[i];
        if (strcmp(p->name, name) != 0)
            continue;
        if (p->type == CV_PARAM_TEXTURE) {
            p->used = true;
            int t = cv_b_lookup(b->float_tex, b->n_float_tex, p->strs[0]);
            if (t < 0)
                t = cv_b_lookup(b->spec_tex, b->n_spec_tex, p->strs[0]);
            if (t < 0)
                return cv_fail(err, "%s:%d:%d: unknown float texture \"%s\"", p->file, p->line,
                               p->col, p->strs[0]);
            *tex = t;
            return true;
        }
        if ((p->type == CV_PARAM_FLOAT || p->type == CV_PARAM_INTEGER) && p->n_nums) {
            p->used = true;
            *val = p->nums[0];
            return true;
        }
        break;
    }
    return true;
}

void cv_blackbody_sensor_rgb(double T, double rgb[3])
{
    double xyz[3] = {0, 0, 0}, peak = planck(2.8977721e-3 / T * 1e9, T);
    for (double l = 360; l <= 830; l += 1) {
        double m[3], v = planck(l, T) / peak;
        cie_xyz(l, m);
        for (int c = 0; c < 3; c++)
            xyz[c] += v * m[c];
    }
    xyz_to_rgb(xyz, rgb);
}
