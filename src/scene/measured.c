/* measured.c: see measured.h. The warps follow the piecewise-linear 2D
 * distributions of Dupuy & Jakob's adaptive parameterisation as pbrt-v4
 * builds them: a slice's data are bilinear patches over a grid on [0,1]^2;
 * the conditional CDF of a row integrates it along x (trapezoids), the
 * marginal CDF integrates the rows' totals along y; both and the data are
 * then divided by the slice's total. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/measured.h"
#include "scene/measured.h"
#include "scene/spectrum.h"

struct block {
    uint32_t *w;
    size_t n, cap;
};

static uint32_t put_floats(struct block *b, const float *v, size_t n)
{
    uint32_t at = (uint32_t)b->n;
    b->w = cv_xgrow(b->w, &b->cap, b->n + n, sizeof(uint32_t));
    memcpy(b->w + b->n, v, n * sizeof(float));
    b->n += n;
    return at;
}

static void set_float(struct block *b, size_t i, float v) { memcpy(&b->w[i], &v, 4); }

static bool shape_is(const struct cv_tensor_field *f, enum cv_tensor_type type, uint32_t ndim)
{
    return f->type == type && f->ndim == ndim;
}

static const struct cv_tensor_field *field(const char *name, const struct cv_tensor_file *t,
                                           const char *key, enum cv_tensor_type type,
                                           uint32_t ndim, struct cv_error *err)
{
    const struct cv_tensor_field *f = cv_tensor_field(t, key);
    if (!f) {
        cv_fail(err, "%s: no field \"%s\": not an RGL BRDF file", name, key);
        return NULL;
    }
    if (!shape_is(f, type, ndim)) {
        cv_fail(err, "%s: field \"%s\" is %s of %u dimensions; an RGL BRDF has %s of %u", name,
                key, cv_tensor_type_name(f->type), f->ndim, cv_tensor_type_name(type), ndim);
        return NULL;
    }
    return f;
}

static float *floats(const struct cv_tensor_field *f)
{
    float *v = cv_xmalloc((f->count ? f->count : 1) * sizeof(float));
    for (uint64_t i = 0; i < f->count; i++)
        v[i] = cv_tensor_f32(f, i);
    return v;
}

/* Writes a table of `slices` slices of nx x ny values (data) with its
 * warp header k; sampled: normalise and build the CDFs. */
static bool put_table(const char *name, const char *what, struct block *b, unsigned k,
                      const float *data, uint32_t nx, uint32_t ny, size_t slices, bool sampled,
                      struct cv_error *err)
{
    size_t hdr = CV_MEAS_H_WARPS + k * CV_MEAS_W_WORDS, nv = (size_t)nx * ny;
    b->w[hdr + CV_MEAS_W_NX] = nx;
    b->w[hdr + CV_MEAS_W_NY] = ny;
    if (!sampled) {
        uint32_t at = put_floats(b, data, slices * nv); /* may move b->w */
        b->w[hdr + CV_MEAS_W_DATA] = at;
        set_float(b, hdr + CV_MEAS_W_SCALE, 1.0f);
        return true;
    }
    float *out = cv_xmalloc(slices * nv * sizeof(float)), *cond = cv_xmalloc(slices * nv * sizeof(float)),
          *marg = cv_xmalloc(slices * ny * sizeof(float));
    bool ok = true;
    for (size_t s = 0; s < slices && ok; s++) {
        const float *d = data + s * nv;
        float *c = cond + s * nv, *m = marg + s * ny;
        for (uint32_t y = 0; y < ny; y++) {
            double sum = 0;
            c[y * nx] = 0;
            for (uint32_t x = 0; x + 1 < nx; x++) {
                sum += 0.5 * ((double)d[y * nx + x] + d[y * nx + x + 1]);
                c[y * nx + x + 1] = (float)sum;
            }
        }
        double sum = 0;
        m[0] = 0;
        for (uint32_t y = 0; y + 1 < ny; y++) {
            sum += 0.5 * ((double)c[(y + 1) * nx - 1] + c[(y + 2) * nx - 1]);
            m[y + 1] = (float)sum;
        }
        if (!(m[ny - 1] > 0) || !isfinite(m[ny - 1])) {
            ok = cv_fail(err, "%s: table \"%s\": slice %zu has no positive integral (%g)", name,
                         what, s, (double)m[ny - 1]);
            break;
        }
        float norm = 1.0f / m[ny - 1];
        for (size_t i = 0; i < nv; i++) {
            c[i] *= norm;
            out[s * nv + i] = d[i] * norm;
        }
        for (uint32_t y = 0; y < ny; y++)
            m[y] *= norm;
    }
    if (ok) {
        /* (put_floats may move b->w: offsets first) */
        uint32_t d_at = put_floats(b, out, slices * nv), m_at = put_floats(b, marg, slices * ny),
                 c_at = put_floats(b, cond, slices * nv);
        b->w[hdr + CV_MEAS_W_DATA] = d_at;
        b->w[hdr + CV_MEAS_W_MARGINAL] = m_at;
        b->w[hdr + CV_MEAS_W_COND] = c_at;
        set_float(b, hdr + CV_MEAS_W_SCALE, (float)(nx - 1) * (float)(ny - 1));
    }
    free(out);
    free(cond);
    free(marg);
    return ok;
}

/* The colour table [phi][theta][channel][y][x]: rgb as given, or the
 * spectra [phi][theta][lambda][y][x] weighted into Rec.709. */
static float *colour_table(const char *name, const struct cv_tensor_file *t, uint64_t nphi,
                           uint64_t ntheta, uint64_t nx, uint64_t ny, struct cv_error *err)
{
    const struct cv_tensor_field *sp = cv_tensor_field(t, "spectra");
    uint64_t nv = nx * ny, slices = nphi * ntheta;
    if (!sp) {
        const struct cv_tensor_field *rgb = cv_tensor_field(t, "rgb");
        if (!rgb) {
            cv_fail(err, "%s: neither \"spectra\" nor \"rgb\": not an RGL BRDF file", name);
            return NULL;
        }
        if (!shape_is(rgb, CV_TENSOR_F32, 5) || rgb->shape[0] != nphi || rgb->shape[1] != ntheta ||
            rgb->shape[2] != 3 || rgb->shape[3] != ny || rgb->shape[4] != nx) {
            cv_fail(err, "%s: field \"rgb\" must be float32 [phi_i][theta_i][3][%llu][%llu]", name,
                    (unsigned long long)ny, (unsigned long long)nx);
            return NULL;
        }
        return floats(rgb);
    }
    const struct cv_tensor_field *wl = field(name, t, "wavelengths", CV_TENSOR_F32, 1, err);
    if (!wl)
        return NULL;
    uint64_t nl = wl->shape[0];
    if (!shape_is(sp, CV_TENSOR_F32, 5) || sp->shape[0] != nphi || sp->shape[1] != ntheta ||
        sp->shape[2] != nl || sp->shape[3] != ny || sp->shape[4] != nx || nl == 0) {
        cv_fail(err,
                "%s: field \"spectra\" must be float32 [phi_i][theta_i][wavelengths][%llu][%llu] "
                "(as \"luminance\"), with at least one wavelength",
                name, (unsigned long long)ny, (unsigned long long)nx);
        return NULL;
    }
    float *lambda = floats(wl);
    for (uint64_t k = 1; k < nl; k++)
        if (!(lambda[k] > lambda[k - 1])) {
            free(lambda);
            cv_fail(err, "%s: \"wavelengths\" must increase", name);
            return NULL;
        }
    double *wt = cv_xmalloc(nl * 3 * sizeof(double));
    cv_spectrum_rgb_weights(lambda, nl, wt);
    float *out = cv_xmalloc(slices * 3 * nv * sizeof(float));
    for (uint64_t s = 0; s < slices; s++)
        for (int c = 0; c < 3; c++)
            for (uint64_t i = 0; i < nv; i++) {
                double v = 0;
                for (uint64_t k = 0; k < nl; k++)
                    v += wt[3 * k + c] * cv_tensor_f32(sp, (s * nl + k) * nv + i);
                out[(s * 3 + c) * nv + i] = (float)v;
            }
    free(wt);
    free(lambda);
    return out;
}

bool cv_measured_tables(const char *name, const struct cv_tensor_file *t, uint32_t **block,
                        size_t *n, struct cv_error *err)
{
    const struct cv_tensor_field *theta_i = field(name, t, "theta_i", CV_TENSOR_F32, 1, err),
                                 *phi_i = theta_i ? field(name, t, "phi_i", CV_TENSOR_F32, 1, err) : NULL,
                                 *ndf = phi_i ? field(name, t, "ndf", CV_TENSOR_F32, 2, err) : NULL,
                                 *sigma = ndf ? field(name, t, "sigma", CV_TENSOR_F32, 2, err) : NULL,
                                 *vndf = sigma ? field(name, t, "vndf", CV_TENSOR_F32, 4, err) : NULL,
                                 *lum = vndf ? field(name, t, "luminance", CV_TENSOR_F32, 4, err) : NULL,
                                 *desc = lum ? field(name, t, "description", CV_TENSOR_U8, 1, err) : NULL,
                                 *jac = desc ? field(name, t, "jacobian", CV_TENSOR_U8, 1, err) : NULL;
    if (!jac)
        return false;
    uint64_t nphi = phi_i->shape[0], ntheta = theta_i->shape[0];
    if (nphi == 0 || ntheta == 0 || jac->shape[0] != 1)
        return cv_fail(err, "%s: phi_i and theta_i need an entry each and jacobian one value", name);
    if (vndf->shape[0] != nphi || vndf->shape[1] != ntheta || lum->shape[0] != nphi ||
        lum->shape[1] != ntheta)
        return cv_fail(err, "%s: \"vndf\" and \"luminance\" must have [phi_i][theta_i] slices", name);
    if (lum->shape[2] != lum->shape[3])
        return cv_fail(err, "%s: \"luminance\" slices must be square", name);
    /* a grid needs two nodes per axis: the patches lie between them */
    const struct cv_tensor_field *grids[4] = {ndf, sigma, vndf, lum};
    for (int g = 0; g < 4; g++) {
        const uint64_t *sh = grids[g]->shape + grids[g]->ndim - 2;
        if (sh[0] < 2 || sh[1] < 2 || sh[0] > (1u << 16) || sh[1] > (1u << 16))
            return cv_fail(err, "%s: field \"%s\": grid %llu x %llu (2 to 65536 nodes a side)",
                           name, grids[g]->name, (unsigned long long)sh[1], (unsigned long long)sh[0]);
    }
    float *phi = floats(phi_i), *theta = floats(theta_i);
    for (uint64_t k = 1; k < nphi || k < ntheta; k++)
        if ((k < nphi && !(phi[k] > phi[k - 1])) || (k < ntheta && !(theta[k] > theta[k - 1]))) {
            free(phi);
            free(theta);
            return cv_fail(err, "%s: phi_i and theta_i must increase", name);
        }
    /* pbrt-v4: fewer than three phi_i entries is an isotropic BRDF; an
     * anisotropic one must cover the full circle (no symmetry reduction) */
    bool iso = nphi <= 2;
    if (!iso) {
        long reduction = lrint(2 * M_PI / (phi[nphi - 1] - phi[0]));
        if (reduction != 1) {
            free(phi);
            free(theta);
            return cv_fail(err, "%s: phi_i covers 1/%ld of the circle; only full circles are supported",
                           name, reduction);
        }
    }
    uint32_t nx = (uint32_t)lum->shape[3], ny = (uint32_t)lum->shape[2];
    float *rgb = colour_table(name, t, nphi, ntheta, nx, ny, err);
    if (!rgb) {
        free(phi);
        free(theta);
        return false;
    }
    struct block b = {0};
    b.w = cv_xcalloc(CV_MEAS_HEADER_WORDS, sizeof(uint32_t));
    b.n = b.cap = CV_MEAS_HEADER_WORDS;
    b.w[CV_MEAS_H_ISOTROPIC] = iso ? 1u : 0u;
    b.w[CV_MEAS_H_NPHI] = (uint32_t)nphi;
    b.w[CV_MEAS_H_NTHETA] = (uint32_t)ntheta;
    uint32_t phi_at = put_floats(&b, phi, nphi), theta_at = put_floats(&b, theta, ntheta);
    b.w[CV_MEAS_H_PHI] = phi_at;
    b.w[CV_MEAS_H_THETA] = theta_at;
    float *d_ndf = floats(ndf), *d_sigma = floats(sigma), *d_vndf = floats(vndf), *d_lum = floats(lum);
    size_t slices = (size_t)(nphi * ntheta);
    bool ok = put_table(name, "ndf", &b, CV_MEAS_NDF, d_ndf, (uint32_t)ndf->shape[1],
                        (uint32_t)ndf->shape[0], 1, false, err) &&
              put_table(name, "sigma", &b, CV_MEAS_SIGMA, d_sigma, (uint32_t)sigma->shape[1],
                        (uint32_t)sigma->shape[0], 1, false, err) &&
              put_table(name, "vndf", &b, CV_MEAS_VNDF, d_vndf, (uint32_t)vndf->shape[3],
                        (uint32_t)vndf->shape[2], slices, true, err) &&
              put_table(name, "luminance", &b, CV_MEAS_LUM, d_lum, nx, ny, slices, true, err) &&
              put_table(name, "rgb", &b, CV_MEAS_RGB, rgb, nx, ny, slices * 3, false, err);
    free(d_ndf);
    free(d_sigma);
    free(d_vndf);
    free(d_lum);
    free(rgb);
    free(phi);
    free(theta);
    if (ok && b.n > UINT32_MAX / 2)
        ok = cv_fail(err, "%s: tables too large", name);
    if (!ok) {
        free(b.w);
        return false;
    }
    *block = b.w;
    *n = b.n;
    return true;
}
