/* conductor_fresnel.c: the RGB Fresnel reflectance of a conductor given
 * by spectra against the cosine of the angle, integrated per wavelength
 * as pbrt-v4 renders it (glsl/shared/conductor_fresnel.h says why). */
#include "scene/conductor_fresnel.h"
#include "scene/fresnel.h"
#include "scene/spectrum.h"

void cv_conductor_fresnel_table(const double *eta, size_t n_eta, const double *k, size_t n_k,
                                double outer, float *table)
{
    double w[3 * CV_SPECTRUM_NM], e[CV_SPECTRUM_NM], kk[CV_SPECTRUM_NM];
    cv_spectrum_rgb_weights_nm(w);
    for (int l = 0; l < CV_SPECTRUM_NM; l++) {
        e[l] = cv_spectrum_at(eta, n_eta, CV_SPECTRUM_NM_MIN + l) / outer;
        kk[l] = cv_spectrum_at(k, n_k, CV_SPECTRUM_NM_MIN + l) / outer;
    }
    for (int i = 0; i < CV_CONDUCTOR_FRESNEL_N; i++) {
        double cos_i = (double)i / (CV_CONDUCTOR_FRESNEL_N - 1), rgb[3] = {0, 0, 0};
        for (int l = 0; l < CV_SPECTRUM_NM; l++) {
            double f = cv_fresnel_complex(cos_i, e[l], kk[l]);
            for (int c = 0; c < 3; c++)
                rgb[c] += w[3 * l + c] * f;
        }
        for (int c = 0; c < 3; c++)
            table[4 * i + c] = (float)rgb[c];
        table[4 * i + 3] = 0;
    }
}
