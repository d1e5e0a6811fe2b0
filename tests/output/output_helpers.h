/* output_helpers.h: scratch folders for the output tests, and a check that
 * a folder holds exactly the files a test expects (no stray temporaries). */
#ifndef CV_TESTS_OUTPUT_HELPERS_H
#define CV_TESTS_OUTPUT_HELPERS_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"

/* A fresh folder under $TMPDIR (or /tmp); newly allocated path. */
static inline char *scratch_dir(const char *tag)
{
    const char *tmp = getenv("TMPDIR");
    char *tmpl = cv_xasprintf("%s/cv-%s-XXXXXX", tmp && *tmp ? tmp : "/tmp", tag);
    if (!mkdtemp(tmpl)) {
        perror(tmpl);
        exit(1);
    }
    return tmpl;
}

/* Number of entries other than . and .., hidden ones included. */
static inline int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
            n++;
    closedir(d);
    return n;
}

/* Removes a flat scratch folder and frees its path. */
static inline void remove_scratch(char *dir)
{
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d))) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            char *p = cv_xasprintf("%s/%s", dir, e->d_name);
            if (unlink(p) != 0)
                rmdir(p);
            free(p);
        }
        closedir(d);
    }
    rmdir(dir);
    free(dir);
}

/* Writes text to path directly (the "older file" a failed write must keep). */
static inline void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        exit(1);
    }
    fputs(text, f);
    fclose(f);
}

static inline bool file_is(const char *path, const char *text)
{
    char buf[256] = { 0 };
    FILE *f = fopen(path, "r");
    if (!f)
        return false;
    size_t n = fread(buf, 1, sizeof(buf) - 1, f);
    fclose(f);
    return n == strlen(text) && memcmp(buf, text, n) == 0;
}

#endif
