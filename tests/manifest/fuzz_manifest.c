/* fuzz_manifest.c: a deterministic mutation fuzzer for the manifest
 * loader. Seeds are the .yaml files of the folders given; each iteration
 * mutates one seed (tests/fuzz_mutate.h) with a fixed-seed PRNG, writes it
 * to a temporary folder (beside links to the seed folders' other files)
 * and loads it with cv_manifest_load. The scenes a
 * manifest names may be missing: loading may fail with an error. It passes
 * when no input crashes, hangs or (under ASan) leaks.
 *   fuzz_manifest ITERATIONS SEED DIR...  */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/log.h"
#include "manifest/manifest.h"
#include "tests/fuzz_mutate.h"

/* YAML structure and the manifest's own keys and values. */
static const char *const dict[] = {
    "\n", " ", "  ", ":", ": ", "- ", "[", "]", "{", "}", ",", "\"", "'", "#", "&a", "*a", "<<: *a\n",
    "!!str ", "!!int ", "---\n", "...\n", "|\n  ", ">\n  ", "\t", "0", "-1", "1e300", "nan", ".inf",
    "4294967296", "99999999999999999999", "true", "null", "~", "", "\xff\xfe", "version: 1\n",
    "jobs:\n", "defaults:\n", "  - name: x\n", "name: ", "scene: ", "output: ", "{name}", "{job}",
    "formats: [exr, png]\n", "spp: ", "seed: ", "max_depth: ", "resolution: [8, 6]\n", "integrator: ",
    "color:\n", "exposure: ", "display: sRGB\n", "view: ", "look: ", "exr:\n", "compression: piz\n",
    "aovs: [albedo, normal, depth]\n", "crop: ", "time_limit: ", "tiles: ", "../", "/",
};

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: fuzz_manifest ITERATIONS SEED DIR...\n");
        return 2;
    }
    long iters = atol(argv[1]);
    cv_fuzz_seed_rng(strtoull(argv[2], NULL, 10));
    static const char *const suffixes[] = {".yaml"};
    struct cv_fuzz_seed seeds[128];
    size_t n_seeds = 0;
    for (int i = 3; i < argc; i++)
        cv_fuzz_read_seeds(argv[i], suffixes, 1, seeds, &n_seeds, 128);
    if (!n_seeds) {
        printf("1..0 # SKIP no seeds\n");
        return 0;
    }
    char dir[] = "/tmp/cv-fuzz-manifest-XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    /* The scenes the seeds name, beside the mutant, so that inputs get past
     * the scene check into the rest of the loader. */
    for (int i = 3; i < argc; i++) {
        DIR *d = opendir(argv[i]);
        struct dirent *e;
        while (d && (e = readdir(d)))
            if (e->d_name[0] != '.' && cv_fuzz_suffix(e->d_name, suffixes, 1) < 0) {
                char from[2200], to[2200];
                snprintf(from, sizeof(from), "%s/%s", argv[i], e->d_name);
                snprintf(to, sizeof(to), "%s/%s", dir, e->d_name);
                char *abs = realpath(from, NULL);
                if (abs && symlink(abs, to) != 0) { /* a name in two folders: the first wins */ }
                free(abs);
            }
        if (d)
            closedir(d);
    }
    char path[64];
    snprintf(path, sizeof(path), "%s/fuzz.yaml", dir);
    FILE *null = fopen("/dev/null", "w");
    cv_log_set_stream(null);
    long loaded = 0, jobs = 0;
    for (long it = 0; it < iters; it++) {
        struct cv_fuzz_seed *s = &seeds[cv_fuzz_rng() % n_seeds];
        size_t len;
        unsigned char *buf = cv_fuzz_mutant(s, dict, sizeof(dict) / sizeof(dict[0]), &len);
        cv_fuzz_write_file(path, buf, len);
        struct cv_manifest *m = NULL;
        struct cv_error err = {0};
        if (cv_manifest_load(path, &m, &err)) {
            loaded++;
            jobs += (long)m->n_jobs;
        }
        cv_manifest_destroy(&m);
        free(buf);
    }
    cv_log_set_stream(NULL);
    fclose(null);
    unlink(path);
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (e->d_name[0] != '.') {
            char p[2200];
            snprintf(p, sizeof(p), "%s/%s", dir, e->d_name);
            unlink(p);
        }
    if (d)
        closedir(d);
    rmdir(dir);
    for (size_t i = 0; i < n_seeds; i++)
        free(seeds[i].data);
    printf("ok 1 - %ld mutated manifests loaded without a crash\n", iters);
    printf("# %ld of %ld inputs still loaded after mutation (%ld jobs)\n", loaded, iters, jobs);
    printf("1..1\n");
    return 0;
}
