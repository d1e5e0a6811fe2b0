/* ply.c: a PLY reader built for speed on binary files (one pass over the
 * bytes, no per-value allocation) and for safety on broken ones (every
 * count is checked against the bytes left before anything is allocated). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "base/file.h"
#include "base/limits.h"
#include "base/mem.h"
#include "scene/ply.h"

enum ptype { T_NONE, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 };
static const int type_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

/* What a vertex property feeds. */
enum role { R_NONE, R_X, R_Y, R_Z, R_NX, R_NY, R_NZ, R_U, R_V, R_INDICES };

struct prop {
    enum ptype type;
    enum ptype count_type;   /* T_NONE: not a list */
    enum role role;
};

struct element {
    char name[32];
    uint64_t count;
    struct prop *props;
    size_t n_props, cap_props;
};

enum format { F_ASCII, F_LE, F_BE };

static enum ptype parse_type(const char *s)
{
    static const struct { const char *n; enum ptype t; } map[] = {
        {"char", T_I8}, {"int8", T_I8}, {"uchar", T_U8}, {"uint8", T_U8},
        {"short", T_I16}, {"int16", T_I16}, {"ushort", T_U16}, {"uint16", T_U16},
        {"int", T_I32}, {"int32", T_I32}, {"uint", T_U32}, {"uint32", T_U32},
        {"float", T_F32}, {"float32", T_F32}, {"double", T_F64}, {"float64", T_F64},
    };
    for (size_t i = 0; i < CV_ARRAY_SIZE(map); i++)
        if (strcmp(s, map[i].n) == 0)
            return map[i].t;
    return T_NONE;
}

static enum role vertex_role(const char *n)
{
    static const struct { const char *n; enum role r; } map[] = {
        {"x", R_X}, {"y", R_Y}, {"z", R_Z}, {"nx", R_NX}, {"ny", R_NY}, {"nz", R_NZ},
        {"u", R_U}, {"v", R_V}, {"s", R_U}, {"t", R_V}, {"texture_u", R_U}, {"texture_v", R_V},
        {"texture_s", R_U}, {"texture_t", R_V},
    };
    for (size_t i = 0; i < CV_ARRAY_SIZE(map); i++)
        if (strcmp(n, map[i].n) == 0)
            return map[i].r;
    return R_NONE;
}

static inline double read_bin(const unsigned char *p, enum ptype t, bool swap)
{
    unsigned char b[8];
    int n = type_size[t];
    if (swap)
        for (int i = 0; i < n; i++)
            b[i] = p[n - 1 - i];
    else
        memcpy(b, p, (size_t)n);
    switch (t) {
    case T_I8: return (int8_t)b[0];
    case T_U8: return b[0];
    case T_I16: { int16_t v; memcpy(&v, b, 2); return v; }
    case T_U16: { uint16_t v; memcpy(&v, b, 2); return v; }
    case T_I32: { int32_t v; memcpy(&v, b, 4); return v; }
    case T_U32: { uint32_t v; memcpy(&v, b, 4); return v; }
    case T_F32: { float v; memcpy(&v, b, 4); return v; }
    case T_F64: { double v; memcpy(&v, b, 8); return v; }
    default: return 0;
    }
}

struct reader {
    const char *name;
    const unsigned char *p, *end;
    enum format fmt;
    bool swap;
};

/* One scalar; false at the end of data or on a bad ascii number. */
static inline bool get(struct reader *r, enum ptype t, double *out)
{
    if (r->fmt != F_ASCII) {
        int n = type_size[t];
        if ((size_t)(r->end - r->p) < (size_t)n)
            return false;
        *out = read_bin(r->p, t, r->swap);
        r->p += n;
        return true;
    }
    while (r->p < r->end && (*r->p == ' ' || *r->p == '\t' || *r->p == '\n' || *r->p == '\r'))
        r->p++;
    if (r->p >= r->end)
        return false;
    char *e;
    /* the buffer is NUL-terminated past end (see callers), so strtod stops */
    *out = strtod((const char *)r->p, &e);
    if ((const unsigned char *)e == r->p || (const unsigned char *)e > r->end)
        return false;
    r->p = (const unsigned char *)e;
    return true;
}

static void free_elements(struct element *el, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(el[i].props);
    free(el);
}

static bool parse_header(const char *name, const unsigned char *data, size_t len,
                         struct element **out_el, size_t *out_n, enum format *fmt,
                         size_t *body, struct cv_error *err)
{
    struct element *el = NULL;
    size_t n_el = 0, cap_el = 0;
    size_t pos = 0;
    int line = 0;
    bool have_format = false;
    char buf[256];
    for (;;) {
        line++;
        size_t start = pos;
        while (pos < len && data[pos] != '\n')
            pos++;
        if (pos >= len) {
            free_elements(el, n_el);
            return cv_fail(err, "%s:%d: PLY header has no end_header", name, line);
        }
        size_t l = pos - start;
        if (l > 0 && data[start + l - 1] == '\r')
            l--;
        pos++;
        if (l >= sizeof(buf)) {
            free_elements(el, n_el);
            return cv_fail(err, "%s:%d: PLY header line too long", name, line);
        }
        memcpy(buf, data + start, l);
        buf[l] = 0;
        char *save, *w = strtok_r(buf, " \t", &save);
        if (line == 1) {
            if (!w || strcmp(w, "ply") != 0) {
                free_elements(el, n_el);
                return cv_fail(err, "%s:1: not a PLY file (no \"ply\" magic)", name);
            }
            continue;
        }
        if (!w || strcmp(w, "comment") == 0 || strcmp(w, "obj_info") == 0)
            continue;
        if (strcmp(w, "end_header") == 0)
            break;
        if (strcmp(w, "format") == 0) {
            char *f = strtok_r(NULL, " \t", &save);
            if (f && strcmp(f, "ascii") == 0)
                *fmt = F_ASCII;
            else if (f && strcmp(f, "binary_little_endian") == 0)
                *fmt = F_LE;
            else if (f && strcmp(f, "binary_big_endian") == 0)
                *fmt = F_BE;
            else {
                free_elements(el, n_el);
                return cv_fail(err, "%s:%d: unknown PLY format \"%s\"", name, line, f ? f : "");
            }
            have_format = true;
        } else if (strcmp(w, "element") == 0) {
            char *n = strtok_r(NULL, " \t", &save), *c = strtok_r(NULL, " \t", &save);
            char *e = NULL;
            unsigned long long cnt = c ? strtoull(c, &e, 10) : 0;
            if (!n || !c || *e || c[0] == '-') {
                free_elements(el, n_el);
                return cv_fail(err, "%s:%d: bad element line", name, line);
            }
            struct element x = {0};
            snprintf(x.name, sizeof(x.name), "%s", n);
            x.count = cnt;
            CV_PUSH(el, n_el, cap_el, x);
        } else if (strcmp(w, "property") == 0) {
            if (n_el == 0) {
                free_elements(el, n_el);
                return cv_fail(err, "%s:%d: property before any element", name, line);
            }
            struct element *cur = &el[n_el - 1];
            struct prop p = {T_NONE, T_NONE, R_NONE};
            char *t = strtok_r(NULL, " \t", &save);
            if (t && strcmp(t, "list") == 0) {
                char *ct = strtok_r(NULL, " \t", &save), *it = strtok_r(NULL, " \t", &save);
                p.count_type = ct ? parse_type(ct) : T_NONE;
                p.type = it ? parse_type(it) : T_NONE;
                if (p.count_type == T_NONE || p.count_type == T_F32 || p.count_type == T_F64)
                    p.type = T_NONE;
            } else {
                p.type = t ? parse_type(t) : T_NONE;
            }
            char *pn = strtok_r(NULL, " \t", &save);
            if (p.type == T_NONE || !pn) {
                free_elements(el, n_el);
                return cv_fail(err, "%s:%d: bad property line", name, line);
            }
            if (strcmp(cur->name, "vertex") == 0 && p.count_type == T_NONE)
                p.role = vertex_role(pn);
            else if (strcmp(cur->name, "face") == 0 && p.count_type != T_NONE &&
                     (strcmp(pn, "vertex_indices") == 0 || strcmp(pn, "vertex_index") == 0))
                p.role = R_INDICES;
            CV_PUSH(cur->props, cur->n_props, cur->cap_props, p);
        } else {
            free_elements(el, n_el);
            return cv_fail(err, "%s:%d: unknown PLY header keyword \"%s\"", name, line, w);
        }
    }
    if (!have_format) {
        free_elements(el, n_el);
        return cv_fail(err, "%s: PLY header has no format line", name);
    }
    *out_el = el;
    *out_n = n_el;
    *body = pos;
    return true;
}

/* Minimum bytes one item of an element takes, to bound counts early. */
static size_t min_size(const struct element *e, enum format fmt)
{
    size_t s = 0;
    for (size_t i = 0; i < e->n_props; i++) {
        const struct prop *p = &e->props[i];
        if (fmt == F_ASCII)
            s += 2;
        else
            s += (size_t)type_size[p->count_type != T_NONE ? p->count_type : p->type];
    }
    return s ? s : 1;
}

bool cv_ply_parse(const char *name, const unsigned char *data, size_t len,
                  struct cv_ply_mesh *m, struct cv_error *err)
{
    memset(m, 0, sizeof(*m));
    struct element *el = NULL;
    size_t n_el = 0, body = 0;
    enum format fmt = F_ASCII;
    if (!parse_header(name, data, len, &el, &n_el, &fmt, &body, err))
        return false;
    struct reader r = {name, data + body, data + len, fmt, false};
    uint16_t one = 1;
    bool little = *(const uint8_t *)&one == 1;
    r.swap = (fmt == F_LE && !little) || (fmt == F_BE && little);

    uint32_t *idx = NULL;
    size_t n_idx = 0, cap_idx = 0, cap_quads = 0;
    bool ok = true, have_v = false;
    for (size_t ei = 0; ei < n_el && ok; ei++) {
        struct element *e = &el[ei];
        if ((uint64_t)(r.end - r.p) / min_size(e, fmt) < e->count) {
            ok = cv_fail(err, "%s: element \"%s\" claims %llu items, more than the file holds",
                         name, e->name, (unsigned long long)e->count);
            break;
        }
        bool is_v = strcmp(e->name, "vertex") == 0 && !have_v;
        if (is_v) {
            have_v = true;
            bool hx = false, hn = false, hu = false;
            for (size_t i = 0; i < e->n_props; i++) {
                enum role ro = e->props[i].role;
                hx |= ro == R_X;
                hn |= ro == R_NX || ro == R_NY || ro == R_NZ;
                hu |= ro == R_U || ro == R_V;
            }
            if (!hx) {
                ok = cv_fail(err, "%s: vertex element has no x/y/z", name);
                break;
            }
            if (e->count > 0xffffffffu) {
                ok = cv_fail(err, "%s: more than 2^32 vertices", name);
                break;
            }
            m->n_verts = (size_t)e->count;
            m->P = cv_xcalloc(m->n_verts * 3 + 1, sizeof(float));
            if (hn)
                m->N = cv_xcalloc(m->n_verts * 3 + 1, sizeof(float));
            if (hu)
                m->uv = cv_xcalloc(m->n_verts * 2 + 1, sizeof(float));
        }
        bool is_f = strcmp(e->name, "face") == 0;
        /* fast path: binary little-endian vertices of float only */
        bool fast = is_v && fmt == F_LE && !r.swap && e->n_props <= 10;
        for (size_t i = 0; fast && i < e->n_props; i++)
            fast = e->props[i].type == T_F32 && e->props[i].count_type == T_NONE;
        if (fast) {
            size_t stride = e->n_props * 4;
            float *dst[10] = {0};
            for (size_t i = 0; i < e->n_props; i++) {
                switch (e->props[i].role) {
                case R_X: dst[i] = m->P; break;
                case R_Y: dst[i] = m->P + 1; break;
                case R_Z: dst[i] = m->P + 2; break;
                case R_NX: dst[i] = m->N; break;
                case R_NY: dst[i] = m->N + 1; break;
                case R_NZ: dst[i] = m->N + 2; break;
                case R_U: dst[i] = m->uv; break;
                case R_V: dst[i] = m->uv + 1; break;
                default: break;
                }
            }
            if (fast) {
                const unsigned char *p = r.p;
                for (size_t v = 0; v < m->n_verts; v++, p += stride)
                    for (size_t i = 0; i < e->n_props; i++)
                        if (dst[i]) {
                            size_t k = (e->props[i].role == R_U || e->props[i].role == R_V) ? 2 : 3;
                            memcpy(dst[i] + v * k, p + i * 4, 4);
                        }
                r.p = p;
                continue;
            }
        }
        /* fast path: binary little-endian faces that are a single list of
         * uchar counts and 32-bit indices (what exporters write) */
        if (is_f && fmt == F_LE && !r.swap && e->n_props == 1 && e->props[0].role == R_INDICES &&
            e->props[0].count_type == T_U8 && (e->props[0].type == T_I32 || e->props[0].type == T_U32)) {
            idx = cv_xgrow(idx, &cap_idx, n_idx + (size_t)e->count * 3, sizeof(uint32_t));
            const unsigned char *p = r.p, *end = r.end;
            uint64_t it;
            for (it = 0; it < e->count; it++) {
                if (p >= end)
                    break;
                unsigned n = *p;
                if ((size_t)(end - p - 1) < (size_t)n * 4)
                    break;
                if (n == 3 && (size_t)(cap_idx - n_idx) >= 3) {
                    memcpy(idx + n_idx, p + 1, 12);
                    n_idx += 3;
                } else if (n >= 3) {
                    uint32_t first, prev = 0;
                    if (n == 4)
                        CV_PUSH(m->quad_first, m->n_quads, cap_quads, n_idx / 3);
                    memcpy(&first, p + 1, 4);
                    for (unsigned j = 2; j < n; j++) {
                        uint32_t x;
                        memcpy(&prev, p + 1 + 4 * (j - 1), 4);
                        memcpy(&x, p + 1 + 4 * j, 4);
                        idx = cv_xgrow(idx, &cap_idx, n_idx + 3, sizeof(uint32_t));
                        idx[n_idx++] = first;
                        idx[n_idx++] = prev;
                        idx[n_idx++] = x;
                    }
                    if (n > 4)
                        m->n_polys++;
                }
                p += 1 + (size_t)n * 4;
            }
            r.p = p;
            if (it < e->count) {
                ok = cv_fail(err, "%s: data ends or is malformed in face %llu", name,
                             (unsigned long long)it);
                break;
            }
            /* negative int32 indices show up as huge: caught by the range check */
            continue;
        }
        for (uint64_t it = 0; it < e->count && ok; it++) {
            for (size_t pi = 0; pi < e->n_props; pi++) {
                struct prop *p = &e->props[pi];
                double v;
                if (p->count_type == T_NONE) {
                    if (!get(&r, p->type, &v)) {
                        ok = cv_fail(err, "%s: data ends or is malformed in element \"%s\" item %llu",
                                     name, e->name, (unsigned long long)it);
                        break;
                    }
                    if (!is_v)
                        continue;
                    size_t k = (size_t)it;
                    switch (p->role) {
                    case R_X: m->P[3 * k] = (float)v; break;
                    case R_Y: m->P[3 * k + 1] = (float)v; break;
                    case R_Z: m->P[3 * k + 2] = (float)v; break;
                    case R_NX: m->N[3 * k] = (float)v; break;
                    case R_NY: m->N[3 * k + 1] = (float)v; break;
                    case R_NZ: m->N[3 * k + 2] = (float)v; break;
                    case R_U: m->uv[2 * k] = (float)v; break;
                    case R_V: m->uv[2 * k + 1] = (float)v; break;
                    default: break;
                    }
                    continue;
                }
                double cnt;
                if (!get(&r, p->count_type, &cnt) || cnt < 0 || cnt != floor(cnt) || cnt > 1e6) {
                    ok = cv_fail(err, "%s: bad list length in element \"%s\" item %llu", name,
                                 e->name, (unsigned long long)it);
                    break;
                }
                size_t n = (size_t)cnt;
                if (!(is_f && p->role == R_INDICES)) {
                    for (size_t j = 0; j < n; j++)
                        if (!get(&r, p->type, &v)) {
                            ok = cv_fail(err, "%s: data ends in a list of element \"%s\"", name, e->name);
                            break;
                        }
                    if (!ok)
                        break;
                    continue;
                }
                uint32_t poly[4] = {0};
                uint32_t first = 0, prev = 0;
                if (n == 4)
                    CV_PUSH(m->quad_first, m->n_quads, cap_quads, n_idx / 3);
                for (size_t j = 0; j < n; j++) {
                    if (!get(&r, p->type, &v)) {
                        ok = cv_fail(err, "%s: data ends or is malformed in face %llu", name,
                                     (unsigned long long)it);
                        break;
                    }
                    if (v < 0 || v > 4294967295.0 || v != floor(v)) {
                        ok = cv_fail(err, "%s: bad vertex index %g in face %llu", name, v,
                                     (unsigned long long)it);
                        break;
                    }
                    uint32_t x = (uint32_t)v;
                    if (j < 4)
                        poly[j] = x;
                    if (j == 0)
                        first = x;
                    else if (j >= 2) {
                        uint32_t tri[3] = {first, prev, x};
                        idx = cv_xgrow(idx, &cap_idx, n_idx + 3, sizeof(uint32_t));
                        memcpy(idx + n_idx, tri, sizeof(tri));
                        n_idx += 3;
                    }
                    prev = x;
                }
                (void)poly;
                if (n > 4)
                    m->n_polys++;
            }
        }
    }
    free_elements(el, n_el);
    if (ok && !have_v)
        ok = cv_fail(err, "%s: no vertex element", name);
    for (size_t i = 0; ok && i < n_idx; i++)
        if (idx[i] >= m->n_verts)
            ok = cv_fail(err, "%s: face index %u out of range (%zu vertices)", name, idx[i], m->n_verts);
    for (size_t i = 0; ok && m->P && i < m->n_verts * 3; i++)
        if (!isfinite(m->P[i]))
            ok = cv_fail(err, "%s: vertex %zu is not finite", name, i / 3);
    if (!ok) {
        free(idx);
        cv_ply_free(m);
        return false;
    }
    m->idx = idx;
    m->n_tris = n_idx / 3;
    return true;
}

bool cv_ply_read(const char *path, struct cv_ply_mesh *m, struct cv_error *err)
{
    unsigned char *data;
    size_t len;
    if (!cv_input_check(path, err))
        return false;
    FILE *f = fopen(path, "rb");
    if (!f)
        return cv_fail(err, "%s: cannot open", path);
    unsigned char magic[2] = {0, 0};
    size_t got = fread(magic, 1, 2, f);
    fclose(f);
    if (got == 2 && magic[0] == 0x1f && magic[1] == 0x8b) {
        gzFile gz = gzopen(path, "rb");
        if (!gz)
            return cv_fail(err, "%s: cannot open", path);
        gzbuffer(gz, 1 << 20);
        size_t cap = 1 << 20;
        len = 0;
        data = cv_xmalloc(cap + 1);
        for (;;) {
            if (len == cap) {
                if ((long long)cap >= CV_MAX_INPUT_BYTES) {
                    cv_fail(err, "%s: more than the %lld bytes an input file may hold, "
                                 "uncompressed", path, CV_MAX_INPUT_BYTES);
                    gzclose(gz);
                    free(data);
                    return false;
                }
                cap *= 2;
                data = cv_xrealloc(data, cap + 1);
            }
            size_t want = cap - len > (1u << 30) ? (1u << 30) : cap - len;
            int n = gzread(gz, data + len, (unsigned)want);
            if (n < 0) {
                int e;
                cv_fail(err, "%s: gzip error: %s", path, gzerror(gz, &e));
                gzclose(gz);
                free(data);
                return false;
            }
            if (n == 0)
                break;
            len += (size_t)n;
        }
        gzclose(gz);
        data[len] = 0;
    } else {
        /* Map binary files instead of copying them (the page cache is the
         * buffer). ASCII needs a NUL after the data for strtod: read those,
         * and files whose size is a page multiple, the usual way. */
        int fd = open(path, O_RDONLY);
        struct stat st;
        if (fd >= 0 && fstat(fd, &st) == 0 && st.st_size > 0 &&
            st.st_size % sysconf(_SC_PAGESIZE) != 0) {
            len = (size_t)st.st_size;
            void *map = mmap(NULL, len, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
            close(fd);
            fd = -1;
            if (map != MAP_FAILED) {
                bool ok = cv_ply_parse(path, map, len, m, err);
                munmap(map, len);
                return ok;
            }
        }
        if (fd >= 0)
            close(fd);
        char *d;
        if (!cv_read_file(path, &d, &len, err))
            return false;
        data = (unsigned char *)d;
    }
    bool ok = cv_ply_parse(path, data, len, m, err);
    free(data);
    return ok;
}

void cv_ply_free(struct cv_ply_mesh *m)
{
    free(m->P);
    free(m->N);
    free(m->uv);
    free(m->idx);
    free(m->quad_first);
    memset(m, 0, sizeof(*m));
}
