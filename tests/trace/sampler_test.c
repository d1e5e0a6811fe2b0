/* sampler_test.c: the shipped sampler GLSL (glsl/trace/sampler.glsl) run
 * through a probe shader. Sobol: for every pixel and dimension pair, each
 * prefix of 2^k samples (k <= 8) is a (0,k,2)-net: every elementary interval
 * of area 2^-k holds exactly one point; samples 2^k..2^(k+1) too, so that
 * passes can stop anywhere on a power of two. Both samplers: values in
 * [0,1), deterministic, different for another seed, pixel or pair, and the
 * independent sampler's mean and variance are uniform's. */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"

#define NS 256
#define NP 3
#define NX 8

static bool run(struct cv_gpu *gpu, struct cv_program *prog, uint32_t sampler, uint32_t seed,
                uint32_t first, float *out)
{
    struct cv_error err = {{0}};
    size_t n = (size_t)NS * NP * NX;
    GLuint buf = cv_buffer_create(n * 8, NULL, "sampler probe", &err);
    if (!buf)
        return false;
    cv_buffer_bind(buf, CV_BIND_PROBE_OUT);
    glUseProgram(prog->id);
    glUniform1ui(glGetUniformLocation(prog->id, "u_n_samples"), NS);
    glUniform1ui(glGetUniformLocation(prog->id, "u_n_pairs"), NP);
    glUniform1ui(glGetUniformLocation(prog->id, "u_n_pixels"), NX);
    glUniform2ui(glGetUniformLocation(prog->id, "u_seed"), seed, 0x9e37u);
    glUniform1ui(glGetUniformLocation(prog->id, "u_sampler"), sampler);
    glUniform1ui(glGetUniformLocation(prog->id, "u_first"), first);
    cv_program_dispatch_1d(prog, n);
    bool ok = cv_buffer_read(buf, 0, n * 8, out, &err);
    cv_buffer_destroy(&buf);
    return ok;
}

/* Points [start, start + 2^k) of one (pixel, pair) form a (0,k,2)-net. */
static bool is_net(const float *p, int start, int k)
{
    int n = 1 << k;
    for (int a = 0; a <= k; a++) {
        int nx = 1 << a, ny = 1 << (k - a);
        char *seen = calloc((size_t)n, 1);
        bool ok = true;
        for (int i = start; i < start + n && ok; i++) {
            int x = (int)(p[2 * i] * nx), y = (int)(p[2 * i + 1] * ny);
            if (x < 0 || x >= nx || y < 0 || y >= ny || seen[y * nx + x]++)
                ok = false;
        }
        free(seen);
        if (!ok)
            return false;
    }
    return true;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cv_program *prog = cv_program_get(gpu, "trace/test/sampler_probe.comp", NULL, &err);
    if (!tap_ok(prog != NULL, "probe compiles: %s", prog ? "" : err.msg))
        return tap_done();
    size_t n = (size_t)NS * NP * NX * 2;
    float *a = malloc(n * 4), *b = malloc(n * 4), *c = malloc(n * 4), *d = malloc(n * 4);
    for (uint32_t smp = 0; smp < 2; smp++) {
        const char *name = smp ? "independent" : "sobol";
        if (!tap_ok(run(gpu, prog, smp, 1, 0, a) && run(gpu, prog, smp, 1, 0, b) &&
                        run(gpu, prog, smp, 2, 0, c),
                    "%s: probe runs", name))
            continue;
        bool range = true;
        for (size_t i = 0; i < n; i++)
            range = range && a[i] >= 0 && a[i] < 1;
        tap_ok(range, "%s: values in [0,1)", name);
        tap_ok(memcmp(a, b, n * 4) == 0, "%s: deterministic", name);
        tap_ok(memcmp(a, c, n * 4) != 0, "%s: another seed, other values", name);
        /* pixel 0 pair 0 against pixel 1 pair 0 and pixel 0 pair 1 */
        tap_ok(memcmp(a, a + 2 * NS * NP, NS * 8) != 0 && memcmp(a, a + 2 * NS, NS * 8) != 0,
               "%s: pixels and pairs are decorrelated", name);
        if (smp == 0) {
            int bad = 0, checked = 0;
            for (int set = 0; set < NP * NX; set++) {
                const float *p = a + (size_t)set * NS * 2;
                for (int k = 1; k <= 8; k++) {
                    checked++;
                    bad += !is_net(p, 0, k);
                    if (k < 8) {
                        checked++;
                        bad += !is_net(p, 1 << k, k);
                    }
                }
            }
            tap_ok(bad == 0, "sobol: %d of %d power-of-two runs are (0,k,2)-nets", checked - bad,
                   checked);
            /* a later first index continues the same sequence */
            tap_ok(run(gpu, prog, 0, 1, 100, d) && memcmp(d, a + 200, 8 * (NS - 100)) == 0,
                   "sobol: samples depend on the index only, not on the batch");
        } else {
            double sum = 0, sq = 0;
            for (size_t i = 0; i < n; i++) {
                sum += a[i];
                sq += a[i] * a[i];
            }
            double mean = sum / n, var = sq / n - mean * mean;
            /* n = 12288: standard error of the mean 0.0026 */
            tap_ok(fabs(mean - 0.5) < 0.01 && fabs(var - 1.0 / 12) < 0.004,
                   "independent: mean %.4f and variance %.4f of uniform", mean, var);
        }
    }
    free(a);
    free(b);
    free(c);
    free(d);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
