/* summarize.c: turns the per-repeat records of cavalry_bench into the bench
 * result: per scene and numeric key the median, min, max and spread of the
 * repeats, as one JSON document, plus a short human table. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/mem.h"
#include "bench/bench.h"

struct scene_runs {
    char name[320];
    struct bench_record *runs;
    int n, cap;
};

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Median, min and max of one key over the runs; false if no run has it. */
static bool stat_of(const struct scene_runs *s, const char *key, double *med, double *lo,
                    double *hi, int *count)
{
    double *v = cv_xmalloc(sizeof(double) * (size_t)(s->n ? s->n : 1));
    int n = 0;
    for (int i = 0; i < s->n; i++) {
        const struct bench_field *f = bench_get(&s->runs[i], key);
        if (f && f->is_num && isfinite(f->num))
            v[n++] = f->num;
    }
    if (n) {
        qsort(v, (size_t)n, sizeof(double), cmp_double);
        *med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
        *lo = v[0];
        *hi = v[n - 1];
        *count = n;
    }
    free(v);
    return n > 0;
}

static void cell(FILE *out, const struct scene_runs *s, const char *key, double scale,
                 const char *fmt, int width)
{
    double med, lo, hi;
    int n;
    char buf[64];
    if (stat_of(s, key, &med, &lo, &hi, &n))
        snprintf(buf, sizeof buf, fmt, med * scale);
    else
        snprintf(buf, sizeof buf, "n/a");
    fprintf(out, " %*s", width, buf);
}

/* The last two parts of a path ("gen-1M-seed1/scene.pbrt"): enough to tell
 * scenes apart in a narrow column. */
static const char *short_name(const char *path)
{
    const char *p = path + strlen(path), *cut = path;
    int slashes = 0;
    while (p > path) {
        if (*--p == '/' && ++slashes == 2) {
            cut = p + 1;
            break;
        }
    }
    size_t n = strlen(cut);
    return n > 30 ? cut + n - 30 : cut;
}

static void print_table(FILE *t, const struct scene_runs *sc, int n_sc)
{
    const struct bench_field *g = bench_get(&sc[0].runs[0], "gpu.renderer");
    const struct bench_field *v = bench_get(&sc[0].runs[0], "gpu.version");
    fprintf(t, "GPU: %s | %s | medians of the repeats\n", g ? g->str : "?", v ? v->str : "?");
    fprintf(t, "%-30s %9s %8s %7s %8s %7s %6s %8s %8s %9s %9s %7s\n", "scene", "tris", "load ms",
            "MB/s", "BVH ms", "SAH", "B/tri", "Mrays/s", "Msmp/s", "1stpass", "N spp ms",
            "peakMiB");
    for (int k = 0; k < n_sc; k++) {
        const struct scene_runs *s = &sc[k];
        fprintf(t, "%-30s", short_name(s->name));
        cell(t, s, "scene.triangles", 1, "%.0f", 9);
        cell(t, s, "load.wall_ms", 1, "%.1f", 8);
        cell(t, s, "load.mb_per_s", 1, "%.0f", 7);
        cell(t, s, "bvh.build_gpu_ms", 1, "%.1f", 8);
        cell(t, s, "bvh.sah_cost", 1, "%.1f", 7);
        cell(t, s, "bvh.bytes_per_triangle", 1, "%.1f", 6);
        cell(t, s, "render.rays_per_s", 1e-6, "%.3g", 8);
        cell(t, s, "render.samples_per_s", 1e-6, "%.3g", 8);
        cell(t, s, "render.first_pass_from_start_ms", 1, "%.0f", 9);
        cell(t, s, "render.time_to_spp_wall_ms", 1, "%.0f", 9);
        cell(t, s, "gpu.peak_used_mib", 1, "%.0f", 7);
        fputc('\n', t);
    }
    /* Each reason once, with the scenes it applies to counted. */
    for (int k = 0; k < n_sc; k++) {
        const struct bench_record *r = &sc[k].runs[0];
        for (int i = 0; i < r->n; i++) {
            const struct bench_field *f = &r->f[i];
            if (f->is_num || strncmp(f->key, "unavailable.", 12))
                continue;
            bool seen = false;
            for (int j = 0; j < k && !seen; j++) {
                const struct bench_field *o = bench_get(&sc[j].runs[0], f->key);
                seen = o && !o->is_num && !strcmp(o->str, f->str);
            }
            if (seen)
                continue;
            int count = 0;
            for (int j = 0; j < n_sc; j++) {
                const struct bench_field *o = bench_get(&sc[j].runs[0], f->key);
                count += o && !o->is_num && !strcmp(o->str, f->str);
            }
            fprintf(t, "unavailable: %s: %s (%d of %d scenes)\n", f->key + 12, f->str, count,
                    n_sc);
        }
    }
}

bool bench_summarize(char **files, int n_files, FILE *json, FILE *table, struct cv_error *err)
{
    struct scene_runs *sc = NULL;
    int n_sc = 0, cap_sc = 0;
    for (int fi = 0; fi < n_files; fi++) {
        FILE *f = fopen(files[fi], "r");
        if (!f)
            return cv_fail(err, "%s: cannot open", files[fi]);
        char line[65536];
        while (fgets(line, sizeof line, f)) {
            struct bench_record r;
            if (!bench_record_parse(line, &r))
                continue;   /* log lines and the like */
            const struct bench_field *name = bench_get(&r, "scene");
            if (!name || name->is_num) {
                bench_record_free(&r);
                continue;
            }
            int k = 0;
            while (k < n_sc && strcmp(sc[k].name, name->str))
                k++;
            if (k == n_sc) {
                if (n_sc == cap_sc) {
                    cap_sc = cap_sc ? 2 * cap_sc : 8;
                    sc = cv_xrealloc(sc, sizeof(*sc) * (size_t)cap_sc);
                }
                memset(&sc[n_sc], 0, sizeof sc[n_sc]);
                snprintf(sc[n_sc].name, sizeof sc[n_sc].name, "%s", name->str);
                n_sc++;
            }
            struct scene_runs *s = &sc[k];
            if (s->n == s->cap) {
                s->cap = s->cap ? 2 * s->cap : 4;
                s->runs = cv_xrealloc(s->runs, sizeof(*s->runs) * (size_t)s->cap);
            }
            s->runs[s->n++] = r;
        }
        fclose(f);
    }
    if (n_sc == 0)
        return cv_fail(err, "no benchmark records found in the input");

    time_t now = time(NULL);
    char date[32];
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    const struct bench_record *first = &sc[0].runs[0];
    fprintf(json, "{\n  \"tool\": \"cavalry_bench\",\n  \"format\": 1,\n  \"date\": \"%s\",\n", date);
    static const char *gpu_keys[] = {"gpu.renderer", "gpu.vendor", "gpu.version",
                                     "gpu.backend", "gpu.device"};
    fputs("  \"gpu\": {", json);
    for (size_t i = 0; i < sizeof gpu_keys / sizeof gpu_keys[0]; i++) {
        const struct bench_field *f = bench_get(first, gpu_keys[i]);
        fprintf(json, "%s", i ? ", " : "");
        bench_json_string(json, gpu_keys[i] + 4);
        fputs(": ", json);
        bench_json_string(json, f && !f->is_num ? f->str : "");
    }
    fputs("},\n  \"scenes\": [\n", json);
    for (int k = 0; k < n_sc; k++) {
        struct scene_runs *s = &sc[k];
        fputs("    {\"scene\": ", json);
        bench_json_string(json, s->name);
        fprintf(json, ", \"repeats\": %d,\n      \"metrics\": {", s->n);
        /* Keys in the order of the first run, numbers only. */
        int printed = 0;
        for (int i = 0; i < s->runs[0].n; i++) {
            const struct bench_field *f = &s->runs[0].f[i];
            if (!f->is_num || !strcmp(f->key, "repeat"))
                continue;
            double med, lo, hi;
            int n;
            if (!stat_of(s, f->key, &med, &lo, &hi, &n))
                continue;
            fprintf(json, "%s\n        ", printed++ ? "," : "");
            bench_json_string(json, f->key);
            fprintf(json, ": {\"median\": %.6g, \"min\": %.6g, \"max\": %.6g, "
                    "\"spread_pct\": %.3g, \"n\": %d}", med, lo, hi,
                    med != 0 ? 100.0 * (hi - lo) / fabs(med) : 0.0, n);
        }
        fputs("\n      },\n      \"info\": {", json);
        printed = 0;
        for (int i = 0; i < s->runs[0].n; i++) {
            const struct bench_field *f = &s->runs[0].f[i];
            if (f->is_num || !strncmp(f->key, "unavailable.", 12) || !strcmp(f->key, "scene"))
                continue;
            fprintf(json, "%s", printed++ ? ", " : "");
            bench_json_string(json, f->key);
            fputs(": ", json);
            bench_json_string(json, f->str);
        }
        fputs("},\n      \"unavailable\": {", json);
        printed = 0;
        for (int i = 0; i < s->runs[0].n; i++) {
            const struct bench_field *f = &s->runs[0].f[i];
            if (f->is_num || strncmp(f->key, "unavailable.", 12))
                continue;
            fprintf(json, "%s", printed++ ? ", " : "");
            bench_json_string(json, f->key + 12);
            fputs(": ", json);
            bench_json_string(json, f->str);
        }
        fprintf(json, "}}%s\n", k + 1 < n_sc ? "," : "");
    }
    fputs("  ]\n}\n", json);

    if (table)
        print_table(table, sc, n_sc);
    for (int k = 0; k < n_sc; k++) {
        for (int i = 0; i < sc[k].n; i++)
            bench_record_free(&sc[k].runs[i]);
        free(sc[k].runs);
    }
    free(sc);
    return true;
}
