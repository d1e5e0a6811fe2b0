/* ply.h: PLY meshes (ascii, binary little/big endian, any scalar types,
 * triangles/quads/polygons split into triangles, normals, uvs, gzip). */
#ifndef CV_SCENE_PLY_H
#define CV_SCENE_PLY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"

struct cv_ply_mesh {
    size_t n_verts, n_tris;
    float *P;         /* 3 per vertex */
    float *N;         /* 3 per vertex, NULL if the file has no nx/ny/nz */
    float *uv;        /* 2 per vertex, NULL if none */
    uint32_t *idx;    /* 3 per triangle, each < n_verts */
    size_t n_quads;   /* faces with 4 vertices (split in two) */
    /* n_quads entries, NULL if none: the first of each quad's two
     * triangles, (v0 v1 v2), which (v0 v2 v3) follows */
    size_t *quad_first;
    size_t n_polys;   /* faces with more than 4 (fan-split) */
};

/* Reads path (gzip-compressed or not, detected by content). Errors name the
 * path and, for the header, the line. */
bool cv_ply_read(const char *path, struct cv_ply_mesh *m, struct cv_error *err);
/* The same from memory (uncompressed); name is for messages. data[len]
 * must be readable and 0 (ascii numbers are read with strtod). */
bool cv_ply_parse(const char *name, const unsigned char *data, size_t len,
                  struct cv_ply_mesh *m, struct cv_error *err);
void cv_ply_free(struct cv_ply_mesh *m);

#endif
