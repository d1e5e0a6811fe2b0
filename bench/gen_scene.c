/* gen_scene.c: writes a pbrt-v4 benchmark scene of an exact triangle count,
 * as one scene.pbrt plus binary little-endian PLY meshes. The scene is built
 * to look like real content rather than a uniform grid: many objects whose
 * size and tessellation span orders of magnitude, clustered and scattered,
 * with transforms baked into the vertices, several material kinds and a mix
 * of area and distant/environment light. The same seed always gives the same
 * bytes. --indirect puts everything in a closed room lit by a lamp that faces
 * a wall, so nearly all light arrives after a bounce. --production makes it
 * look like product and interior work instead: dozens of materials (coated
 * plastics and conductors among them), image textures of several sizes and
 * texture coordinates on every mesh, so that shading and texture fetches cost
 * what they cost in real scenes. */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- deterministic random numbers (splitmix64) ---- */

static uint64_t rng_state;

static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [0,1). */
static double rng_uniform(void)
{
    return (double)(rng_next() >> 11) * (1.0 / 9007199254740992.0);
}

static double rng_range(double a, double b)
{
    return a + (b - a) * rng_uniform();
}

static double rng_gauss(void)
{
    double u = rng_uniform(), v = rng_uniform();
    return sqrt(-2.0 * log(1.0 - u)) * cos(2.0 * M_PI * v);
}

/* ---- mesh being built: positions, optional normals, triangles ---- */

struct mesh {
    float *pos, *nrm;          /* 3 floats per vertex */
    float *uv;                 /* 2 floats per vertex, when has_uv */
    uint32_t *idx;             /* 3 per triangle */
    size_t nv, nt, cap_v, cap_t;
    bool has_normals, has_uv;
};

static void *grow(void *p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return p;
    size_t c = *cap ? *cap : 1024;
    while (c < need)
        c *= 2;
    void *q = realloc(p, c * elem);
    if (!q) {
        fprintf(stderr, "gen_scene: out of memory\n");
        exit(1);
    }
    *cap = c;
    return q;
}

static void mesh_reset(struct mesh *m, bool normals)
{
    m->nv = m->nt = 0;
    m->has_normals = normals;
    m->has_uv = false;
}

static uint32_t mesh_vertex(struct mesh *m, double x, double y, double z,
                            double nx, double ny, double nz)
{
    size_t cv = m->cap_v;
    m->pos = grow(m->pos, &cv, m->nv + 1, 3 * sizeof(float));
    cv = m->cap_v;
    m->nrm = grow(m->nrm, &cv, m->nv + 1, 3 * sizeof(float));
    cv = m->cap_v;
    m->uv = grow(m->uv, &cv, m->nv + 1, 2 * sizeof(float));
    m->cap_v = cv;
    float *p = m->pos + 3 * m->nv, *n = m->nrm + 3 * m->nv;
    p[0] = (float)x, p[1] = (float)y, p[2] = (float)z;
    n[0] = (float)nx, n[1] = (float)ny, n[2] = (float)nz;
    return (uint32_t)m->nv++;
}

static void mesh_tri(struct mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    m->idx = grow(m->idx, &m->cap_t, m->nt + 1, 3 * sizeof(uint32_t));
    uint32_t *t = m->idx + 3 * m->nt++;
    t[0] = a, t[1] = b, t[2] = c;
}

/* ---- shapes, in object space ---- */

/* A cube of n x n quads per face; `round` pushes the points onto the unit
 * sphere (no poles, no degenerate triangles), `bumps` displaces them along
 * the normal with a few random lobes. */
static void shape_cube(struct mesh *m, int n, bool round, int bumps)
{
    /* Faces in the order +x -x +y -y +z -z; (u, v, w) cyclic, so u x v = w. */
    static const int axes[3][3] = {{1, 2, 0}, {2, 0, 1}, {0, 1, 2}};
    double lobe[8][4];
    for (int i = 0; i < bumps && i < 8; i++) {
        double a = rng_range(0, 2 * M_PI), b = rng_range(-1, 1);
        double s = sqrt(1 - b * b);
        lobe[i][0] = s * cos(a), lobe[i][1] = s * sin(a), lobe[i][2] = b;
        lobe[i][3] = rng_range(2, 9);           /* frequency */
    }
    for (int f = 0; f < 6; f++) {
        double sign = (f & 1) ? -1.0 : 1.0;
        int u = axes[f / 2][0], v = axes[f / 2][1], w = axes[f / 2][2];
        uint32_t base = (uint32_t)m->nv;
        for (int j = 0; j <= n; j++) {
            for (int i = 0; i <= n; i++) {
                double p[3];
                p[u] = -1 + 2.0 * i / n;
                p[v] = -1 + 2.0 * j / n;
                p[w] = sign;
                double nn[3] = {0, 0, 0};
                nn[w] = sign;
                if (round) {
                    double l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                    for (int k = 0; k < 3; k++)
                        p[k] /= l, nn[k] = p[k];
                    if (bumps) {
                        double r = 1;
                        for (int b = 0; b < bumps && b < 8; b++) {
                            double d = p[0] * lobe[b][0] + p[1] * lobe[b][1] + p[2] * lobe[b][2];
                            r += 0.12 * sin(lobe[b][3] * d + b);
                        }
                        for (int k = 0; k < 3; k++)
                            p[k] *= r;
                    }
                }
                mesh_vertex(m, p[0], p[1], p[2], nn[0], nn[1], nn[2]);
            }
        }
        /* Winding so that the face normal points outwards for every face. */
        bool flip = sign < 0;
        for (int j = 0; j < n; j++) {
            for (int i = 0; i < n; i++) {
                uint32_t a = base + (uint32_t)(j * (n + 1) + i);
                uint32_t b = a + 1, c = a + (uint32_t)(n + 1), d = c + 1;
                if (flip) {
                    mesh_tri(m, a, c, b);
                    mesh_tri(m, b, c, d);
                } else {
                    mesh_tri(m, a, b, c);
                    mesh_tri(m, b, d, c);
                }
            }
        }
    }
    if (round && bumps) {
        /* Normals of the displaced surface: accumulate face normals. */
        memset(m->nrm, 0, m->nv * 3 * sizeof(float));
        for (size_t t = 0; t < m->nt; t++) {
            uint32_t *id = m->idx + 3 * t;
            float *a = m->pos + 3 * id[0], *b = m->pos + 3 * id[1], *c = m->pos + 3 * id[2];
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
            for (int k = 0; k < 3; k++)
                for (int q = 0; q < 3; q++)
                    m->nrm[3 * id[k] + q] += cr[q];
        }
        for (size_t i = 0; i < m->nv; i++) {
            float *nn = m->nrm + 3 * i;
            float l = sqrtf(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            if (l > 0)
                nn[0] /= l, nn[1] /= l, nn[2] /= l;
        }
    }
}

/* Torus in the xz plane, major radius 1, minor radius r. */
static void shape_torus(struct mesh *m, int nu, int nv, double r)
{
    for (int j = 0; j < nv; j++) {
        double b = 2 * M_PI * j / nv;
        for (int i = 0; i < nu; i++) {
            double a = 2 * M_PI * i / nu;
            double cx = cos(a), cz = sin(a);
            double nx = cos(b) * cx, ny = sin(b), nz = cos(b) * cz;
            mesh_vertex(m, cx + r * nx, r * ny, cz + r * nz, nx, ny, nz);
        }
    }
    for (int j = 0; j < nv; j++) {
        for (int i = 0; i < nu; i++) {
            uint32_t a = (uint32_t)(j * nu + i);
            uint32_t b = (uint32_t)(j * nu + (i + 1) % nu);
            uint32_t c = (uint32_t)(((j + 1) % nv) * nu + i);
            uint32_t d = (uint32_t)(((j + 1) % nv) * nu + (i + 1) % nu);
            mesh_tri(m, a, c, b);
            mesh_tri(m, b, c, d);
        }
    }
}

/* Gently rolling terrain of exactly `tris` triangles over [-h,h]^2 at y=0:
 * it takes whatever is left of the budget so the total is exact. */
static void shape_ground(struct mesh *m, uint64_t tris, double h, double amp)
{
    uint64_t cols = (uint64_t)ceil(sqrt((double)tris / 2.0));
    if (cols < 1)
        cols = 1;
    uint64_t rows = (tris + 2 * cols - 1) / (2 * cols);
    for (uint64_t j = 0; j <= rows; j++) {
        for (uint64_t i = 0; i <= cols; i++) {
            double x = -h + 2 * h * (double)i / (double)cols;
            double z = -h + 2 * h * (double)j / (double)rows;
            double y = amp * (sin(x * 0.11) * cos(z * 0.07) + 0.3 * sin(x * 0.5 + z * 0.3));
            double dx = amp * (0.11 * cos(x * 0.11) * cos(z * 0.07) + 0.15 * cos(x * 0.5 + z * 0.3));
            double dz = amp * (-0.07 * sin(x * 0.11) * sin(z * 0.07) + 0.09 * cos(x * 0.5 + z * 0.3));
            double l = sqrt(dx * dx + 1 + dz * dz);
            mesh_vertex(m, x, y, z, -dx / l, 1 / l, -dz / l);
        }
    }
    uint64_t emitted = 0;
    for (uint64_t j = 0; j < rows && emitted < tris; j++) {
        for (uint64_t i = 0; i < cols && emitted < tris; i++) {
            uint32_t a = (uint32_t)(j * (cols + 1) + i);
            uint32_t b = a + 1, c = a + (uint32_t)(cols + 1), d = c + 1;
            mesh_tri(m, a, c, b);
            if (++emitted < tris) {
                mesh_tri(m, b, c, d);
                emitted++;
            }
        }
    }
}

/* ---- texture coordinates ---- */

/* Spherical coordinates of the object-space position: every shape is built
 * around the origin, so this covers each with one image (a seam and pinched
 * poles are of no matter to a benchmark). Call before mesh_apply. */
static void mesh_uv_spherical(struct mesh *m, double repeat)
{
    for (size_t i = 0; i < m->nv; i++) {
        const float *p = m->pos + 3 * i;
        double r = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
        double u = atan2(p[2], p[0]) / (2 * M_PI) + 0.5;
        double v = r > 0 ? acos(p[1] / r) / M_PI : 0.5;
        m->uv[2 * i] = (float)(u * repeat), m->uv[2 * i + 1] = (float)(v * repeat);
    }
    m->has_uv = true;
}

/* Planar coordinates in xz, one repeat every `period` units (the ground). */
static void mesh_uv_planar(struct mesh *m, double period)
{
    for (size_t i = 0; i < m->nv; i++) {
        m->uv[2 * i] = (float)(m->pos[3 * i] / period);
        m->uv[2 * i + 1] = (float)(m->pos[3 * i + 2] / period);
    }
    m->has_uv = true;
}

/* ---- transforms baked into the vertices ---- */

struct xform {
    double r[3][3];            /* rotation times per-axis scale */
    double n[3][3];            /* rotation divided by scale: for normals */
    double t[3];
};

static void xform_make(struct xform *x, const double scale[3], double yaw,
                       double pitch, double roll, const double t[3])
{
    double cy = cos(yaw), sy = sin(yaw), cp = cos(pitch), sp = sin(pitch);
    double cr = cos(roll), sr = sin(roll);
    /* R = Ry(yaw) * Rx(pitch) * Rz(roll) */
    double R[3][3] = {
        {cy * cr + sy * sp * sr, -cy * sr + sy * sp * cr, sy * cp},
        {cp * sr, cp * cr, -sp},
        {-sy * cr + cy * sp * sr, sy * sr + cy * sp * cr, cy * cp},
    };
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            x->r[i][j] = R[i][j] * scale[j];
            x->n[i][j] = R[i][j] / scale[j];
        }
        x->t[i] = t[i];
    }
}

static void mesh_apply(struct mesh *m, const struct xform *x)
{
    for (size_t i = 0; i < m->nv; i++) {
        float *p = m->pos + 3 * i, *n = m->nrm + 3 * i;
        double q[3], k[3];
        for (int r = 0; r < 3; r++) {
            q[r] = x->r[r][0] * p[0] + x->r[r][1] * p[1] + x->r[r][2] * p[2] + x->t[r];
            k[r] = x->n[r][0] * n[0] + x->n[r][1] * n[1] + x->n[r][2] * n[2];
        }
        double l = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
        if (l == 0)
            l = 1;
        for (int r = 0; r < 3; r++)
            p[r] = (float)q[r], n[r] = (float)(k[r] / l);
    }
}

static void mesh_y_range(const struct mesh *m, double *lo, double *hi)
{
    *lo = INFINITY, *hi = -INFINITY;
    for (size_t i = 0; i < m->nv; i++) {
        double y = m->pos[3 * i + 1];
        if (y < *lo)
            *lo = y;
        if (y > *hi)
            *hi = y;
    }
}

/* ---- output ---- */

static char out_dir[4096];
static uint64_t bytes_written;

static bool write_all(FILE *f, const void *data, size_t n, const char *path)
{
    if (n && fwrite(data, 1, n, f) != n) {
        fprintf(stderr, "gen_scene: %s: write failed: %s\n", path, strerror(errno));
        return false;
    }
    bytes_written += n;
    return true;
}

static void put_u32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)v, p[1] = (unsigned char)(v >> 8);
    p[2] = (unsigned char)(v >> 16), p[3] = (unsigned char)(v >> 24);
}

static void put_f32(unsigned char *p, float f)
{
    uint32_t v;
    memcpy(&v, &f, 4);
    put_u32(p, v);
}

/* One big buffer per file: the header, vertices and faces are packed into it
 * and written with a single fwrite, so the generator runs at disk speed. */
static unsigned char *ply_buf;
static size_t ply_cap;

static bool mesh_write_ply(const struct mesh *m, const char *name)
{
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", out_dir, name);
    char header[512];
    int hl = snprintf(header, sizeof header,
                      "ply\nformat binary_little_endian 1.0\n"
                      "comment written by cavalry bench/gen_scene\n"
                      "element vertex %zu\n"
                      "property float x\nproperty float y\nproperty float z\n%s%s"
                      "element face %zu\n"
                      "property list uchar int vertex_indices\nend_header\n",
                      m->nv,
                      m->has_normals ? "property float nx\nproperty float ny\nproperty float nz\n" : "",
                      m->has_uv ? "property float u\nproperty float v\n" : "",
                      m->nt);
    size_t vsize = 12 + (m->has_normals ? 12 : 0) + (m->has_uv ? 8 : 0);
    size_t total = (size_t)hl + m->nv * vsize + m->nt * 13;
    ply_buf = grow(ply_buf, &ply_cap, total, 1);
    unsigned char *p = ply_buf;
    memcpy(p, header, (size_t)hl);
    p += hl;
    for (size_t i = 0; i < m->nv; i++) {
        for (int k = 0; k < 3; k++, p += 4)
            put_f32(p, m->pos[3 * i + k]);
        if (m->has_normals)
            for (int k = 0; k < 3; k++, p += 4)
                put_f32(p, m->nrm[3 * i + k]);
        if (m->has_uv)
            for (int k = 0; k < 2; k++, p += 4)
                put_f32(p, m->uv[2 * i + k]);
    }
    for (size_t t = 0; t < m->nt; t++) {
        *p++ = 3;
        for (int k = 0; k < 3; k++, p += 4)
            put_u32(p, m->idx[3 * t + k]);
    }
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "gen_scene: %s: %s\n", path, strerror(errno));
        return false;
    }
    bool ok = write_all(f, ply_buf, total, path);
    if (fclose(f) != 0 && ok) {
        fprintf(stderr, "gen_scene: %s: %s\n", path, strerror(errno));
        ok = false;
    }
    return ok;
}

/* ---- scene assembly ---- */

enum kind { K_SPHERE, K_BLOB, K_TORUS, K_BOX, K_PANEL, K_COUNT };
static const char *kind_name[K_COUNT] = {"sphere", "blob", "torus", "box", "panel"};

static const char *materials[] = {
    "diffuse_white", "diffuse_red", "diffuse_green", "diffuse_clay",
    "gold", "copper_rough", "aluminium", "glass", "coated_blue", "coated_ivory",
};

static void write_materials(FILE *f)
{
    fputs("MakeNamedMaterial \"diffuse_white\" \"string type\" \"diffuse\"\n"
          "    \"rgb reflectance\" [ 0.75 0.75 0.75 ]\n"
          "MakeNamedMaterial \"diffuse_red\" \"string type\" \"diffuse\"\n"
          "    \"rgb reflectance\" [ 0.63 0.07 0.05 ]\n"
          "MakeNamedMaterial \"diffuse_green\" \"string type\" \"diffuse\"\n"
          "    \"rgb reflectance\" [ 0.12 0.45 0.09 ]\n"
          "MakeNamedMaterial \"diffuse_clay\" \"string type\" \"diffuse\"\n"
          "    \"rgb reflectance\" [ 0.55 0.38 0.25 ]\n"
          "MakeNamedMaterial \"gold\" \"string type\" \"conductor\"\n"
          "    \"spectrum eta\" [ \"metal-Au-eta\" ] \"spectrum k\" [ \"metal-Au-k\" ]\n"
          "    \"float roughness\" [ 0.02 ]\n"
          "MakeNamedMaterial \"copper_rough\" \"string type\" \"conductor\"\n"
          "    \"spectrum eta\" [ \"metal-Cu-eta\" ] \"spectrum k\" [ \"metal-Cu-k\" ]\n"
          "    \"float roughness\" [ 0.25 ]\n"
          "MakeNamedMaterial \"aluminium\" \"string type\" \"conductor\"\n"
          "    \"spectrum eta\" [ \"metal-Al-eta\" ] \"spectrum k\" [ \"metal-Al-k\" ]\n"
          "    \"float roughness\" [ 0.08 ]\n"
          "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\"\n"
          "    \"float eta\" [ 1.5 ]\n"
          "MakeNamedMaterial \"coated_blue\" \"string type\" \"coateddiffuse\"\n"
          "    \"rgb reflectance\" [ 0.08 0.15 0.55 ] \"float roughness\" [ 0.05 ]\n"
          "MakeNamedMaterial \"coated_ivory\" \"string type\" \"coateddiffuse\"\n"
          "    \"rgb reflectance\" [ 0.8 0.75 0.62 ] \"float roughness\" [ 0.2 ]\n\n", f);
}

/* ---- production look: image textures and many materials ---- */

/* A few large textures and more small ones, as real scenes have. */
static const int tex_sizes[] = {2048, 1024, 1024, 512, 512, 512, 256, 256,
                                256, 256, 128, 128, 64, 64, 64, 64};
#define N_TEX ((int)(sizeof tex_sizes / sizeof tex_sizes[0]))
#define N_PROD_MATERIALS 64

/* Value noise on an integer lattice, hashed from the seed: [0,1). */
static double lattice(int x, int y, uint32_t seed)
{
    uint32_t h = (uint32_t)x * 0x8da6b343u ^ (uint32_t)y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 13, h *= 0x5bd1e995u, h ^= h >> 15;
    return (h & 0xffffff) / 16777216.0;
}

static double value_noise(double u, double v, uint32_t seed)
{
    int x = (int)floor(u), y = (int)floor(v);
    double fx = u - x, fy = v - y;
    fx = fx * fx * (3 - 2 * fx), fy = fy * fy * (3 - 2 * fy);
    double a = lattice(x, y, seed), b = lattice(x + 1, y, seed);
    double c = lattice(x, y + 1, seed), d = lattice(x + 1, y + 1, seed);
    return (a + (b - a) * fx) * (1 - fy) + (c + (d - c) * fx) * fy;
}

/* DIR/textures/tex_NN.tga: uncompressed 24-bit TGA (read by Cavalry through
 * stb_image and by pbrt-v4), a pattern that tiles: checks, stripes, wood-like
 * rings or cloudy noise between two random colours. */
static bool write_texture(int index, int size)
{
    char path[8192];
    snprintf(path, sizeof path, "%s/textures/tex_%02d.tga", out_dir, index);
    size_t n = 18 + (size_t)3 * size * size;
    unsigned char *img = calloc(1, n);
    if (!img) {
        fprintf(stderr, "gen_scene: out of memory\n");
        return false;
    }
    img[2] = 2;                                   /* uncompressed true colour */
    img[12] = (unsigned char)(size & 255), img[13] = (unsigned char)(size >> 8);
    img[14] = (unsigned char)(size & 255), img[15] = (unsigned char)(size >> 8);
    img[16] = 24;
    double c0[3], c1[3];
    for (int k = 0; k < 3; k++)
        c0[k] = rng_range(0.05, 0.9), c1[k] = rng_range(0.05, 0.9);
    int pattern = index % 4, cells = 2 << (int)(rng_uniform() * 4);
    uint32_t seed = (uint32_t)rng_next();
    for (int y = 0; y < size; y++) {
        for (int x = 0; x < size; x++) {
            double u = (x + 0.5) / size, v = (y + 0.5) / size, t;
            double grain = value_noise(u * 64, v * 64, seed ^ 0x55u);
            switch (pattern) {
            case 0: t = ((int)(u * cells) + (int)(v * cells)) & 1; break;
            case 1: t = 0.5 + 0.5 * sin(2 * M_PI * cells * (u + 0.05 * grain)); break;
            case 2: {
                double du = u - 0.5, dv = v - 0.5;
                t = 0.5 + 0.5 * sin(2 * M_PI * cells * sqrt(du * du + dv * dv) + 3 * grain);
                break;
            }
            default:
                t = 0.5 * value_noise(u * cells, v * cells, seed) +
                    0.3 * value_noise(u * cells * 4, v * cells * 4, seed + 1) + 0.2 * grain;
                break;
            }
            t = 0.85 * t + 0.15 * grain;
            unsigned char *px = img + 18 + 3 * ((size_t)y * size + x);
            for (int k = 0; k < 3; k++) {
                double c = c0[k] + (c1[k] - c0[k]) * t;
                px[2 - k] = (unsigned char)(255.0 * pow(c, 1 / 2.2) + 0.5);   /* BGR, sRGB */
            }
        }
    }
    FILE *f = fopen(path, "wb");
    bool ok = f && write_all(f, img, n, path);
    if (!f || (fclose(f) != 0 && ok)) {
        fprintf(stderr, "gen_scene: %s: %s\n", path, strerror(errno));
        ok = false;
    }
    free(img);
    return ok;
}

static const char *const metals[] = {"Au", "Cu", "Al", "Ag", "CuZn"};

/* Textures tex_NN and materials prod_NN: textured and plain diffuse, coated
 * plastics (plain and textured), coated conductors, rough and polished
 * conductors, a little glass. */
static void write_production_materials(FILE *f)
{
    for (int t = 0; t < N_TEX; t++)
        fprintf(f, "Texture \"tex_%02d\" \"spectrum\" \"imagemap\"\n"
                "    \"string filename\" [ \"textures/tex_%02d.tga\" ]\n", t, t);
    for (int i = 0; i < N_PROD_MATERIALS; i++) {
        int tex = (int)(rng_next() % N_TEX);
        const char *metal = metals[rng_next() % (sizeof metals / sizeof metals[0])];
        double r = rng_range(0.05, 0.85), g = rng_range(0.05, 0.85), b = rng_range(0.05, 0.85);
        fprintf(f, "MakeNamedMaterial \"prod_%02d\"", i);
        switch (i % 8) {
        case 0:
        case 6:
            fprintf(f, " \"string type\" \"diffuse\" \"texture reflectance\" \"tex_%02d\"\n", tex);
            break;
        case 1:
            fprintf(f, " \"string type\" \"diffuse\" \"rgb reflectance\" [ %.3f %.3f %.3f ]\n",
                    r, g, b);
            break;
        case 2:
            fprintf(f, " \"string type\" \"coateddiffuse\" \"texture reflectance\" \"tex_%02d\"\n"
                    "    \"float roughness\" [ %.3f ]\n", tex, rng_range(0, 0.3));
            break;
        case 3:
            fprintf(f, " \"string type\" \"coateddiffuse\" \"rgb reflectance\" [ %.3f %.3f %.3f ]\n"
                    "    \"float roughness\" [ %.3f ]\n", r, g, b, rng_range(0, 0.15));
            break;
        case 4:
            fprintf(f, " \"string type\" \"coatedconductor\"\n"
                    "    \"spectrum conductor.eta\" [ \"metal-%s-eta\" ]"
                    " \"spectrum conductor.k\" [ \"metal-%s-k\" ]\n"
                    "    \"float conductor.roughness\" [ %.3f ]"
                    " \"float interface.roughness\" [ %.3f ]\n",
                    metal, metal, rng_range(0.05, 0.4), rng_range(0, 0.1));
            break;
        case 5:
            fprintf(f, " \"string type\" \"conductor\"\n"
                    "    \"spectrum eta\" [ \"metal-%s-eta\" ] \"spectrum k\" [ \"metal-%s-k\" ]\n"
                    "    \"float roughness\" [ %.3f ]\n", metal, metal, rng_range(0.01, 0.4));
            break;
        default:
            if (i % 32 == 7)
                fprintf(f, " \"string type\" \"dielectric\" \"float eta\" [ 1.5 ]\n");
            else
                fprintf(f, " \"string type\" \"conductor\" \"rgb reflectance\" [ %.3f %.3f %.3f ]\n"
                        "    \"float roughness\" [ %.3f ]\n", r, g, b, rng_range(0.02, 0.3));
            break;
        }
    }
    fputc('\n', f);
}

struct opts {
    uint64_t triangles;
    uint64_t seed;
    const char *out;
    bool indirect, production;
    int width, height, spp;
};

static void usage(FILE *f)
{
    fputs("usage: gen_scene --triangles N --out DIR [--seed S] [--indirect] [--production]\n"
          "                 [--width W] [--height H] [--spp N]\n"
          "Writes DIR/scene.pbrt and DIR/geometry/*.ply (binary little-endian)\n"
          "with exactly N triangles. --indirect: closed room, lamp facing a wall.\n"
          "--production: 64 materials (coated plastics and conductors among them)\n"
          "and 16 image textures of 64 to 2048 texels in DIR/textures.\n", f);
}

static bool parse_u64(const char *s, uint64_t *v)
{
    char *end;
    errno = 0;
    double d = strtod(s, &end);
    if (errno || end == s)
        return false;
    /* Accept 4M, 1.5M, 300k as well as plain numbers. */
    if (*end == 'k' || *end == 'K')
        d *= 1e3, end++;
    else if (*end == 'm' || *end == 'M')
        d *= 1e6, end++;
    if (*end || d < 0 || d > 4e9)
        return false;
    *v = (uint64_t)llround(d);
    return true;
}

static bool parse_args(int argc, char **argv, struct opts *o)
{
    *o = (struct opts){.seed = 1, .width = 1280, .height = 720, .spp = 64};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        uint64_t v;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            exit(0);
        } else if (!strcmp(a, "--indirect")) {
            o->indirect = true;
        } else if (!strcmp(a, "--production")) {
            o->production = true;
        } else if (i + 1 < argc && !strcmp(a, "--out")) {
            o->out = argv[++i];
        } else if (i + 1 < argc && (!strcmp(a, "--triangles") || !strcmp(a, "--seed") ||
                                    !strcmp(a, "--width") || !strcmp(a, "--height") ||
                                    !strcmp(a, "--spp"))) {
            if (!parse_u64(argv[++i], &v)) {
                fprintf(stderr, "gen_scene: %s: bad number \"%s\"\n", a, argv[i]);
                return false;
            }
            if (!strcmp(a, "--triangles"))
                o->triangles = v;
            else if (!strcmp(a, "--seed"))
                o->seed = v;
            else if (v < 1 || v > 65536) {
                fprintf(stderr, "gen_scene: %s out of range\n", a);
                return false;
            } else if (!strcmp(a, "--width"))
                o->width = (int)v;
            else if (!strcmp(a, "--height"))
                o->height = (int)v;
            else
                o->spp = (int)v;
        } else {
            fprintf(stderr, "gen_scene: unknown or incomplete argument \"%s\"\n", a);
            usage(stderr);
            return false;
        }
    }
    if (!o->out || !o->triangles) {
        usage(stderr);
        return false;
    }
    if (o->triangles < 2000) {
        fprintf(stderr, "gen_scene: --triangles must be at least 2000\n");
        return false;
    }
    if (o->triangles > 2000000000ull) {
        fprintf(stderr, "gen_scene: --triangles above 2e9 is not supported\n");
        return false;
    }
    return true;
}

static bool make_dir(const char *path)
{
    if (mkdir(path, 0777) == 0 || errno == EEXIST)
        return true;
    fprintf(stderr, "gen_scene: mkdir %s: %s\n", path, strerror(errno));
    return false;
}

/* Triangle count of a shape for tessellation parameter n. */
static uint64_t shape_tris(enum kind k, int n)
{
    if (k == K_TORUS)
        return (uint64_t)8 * n * n;    /* nu = 2*nv*2, nv = n */
    return (uint64_t)12 * n * n;
}

static int shape_param(enum kind k, double budget)
{
    double n = k == K_TORUS ? sqrt(budget / 8) : sqrt(budget / 12);
    return n < 2 ? 2 : (int)n;
}

static double elapsed_s(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) + 1e-9 * (double)(t.tv_nsec - t0->tv_nsec);
}

int main(int argc, char **argv)
{
    struct opts o;
    if (!parse_args(argc, argv, &o))
        return 2;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    rng_state = o.seed * 0x2545f4914f6cdd1dull + 0x1234567ull;

    snprintf(out_dir, sizeof out_dir, "%s", o.out);
    char geo[4200];
    snprintf(geo, sizeof geo, "%s/geometry", o.out);
    if (!make_dir(o.out) || !make_dir(geo))
        return 1;
    if (o.production) {
        char tex[4200];
        snprintf(tex, sizeof tex, "%s/textures", o.out);
        if (!make_dir(tex))
            return 1;
        for (int t = 0; t < N_TEX; t++)
            if (!write_texture(t, tex_sizes[t]))
                return 1;
    }
    char scene_path[4200];
    snprintf(scene_path, sizeof scene_path, "%s/scene.pbrt", o.out);
    FILE *sf = fopen(scene_path, "w");
    if (!sf) {
        fprintf(stderr, "gen_scene: %s: %s\n", scene_path, strerror(errno));
        return 1;
    }

    /* World layout: outdoor field of half-size H, or a closed room. */
    const double H = o.indirect ? 30.0 : 60.0;
    const double room_h = 24.0;

    fprintf(sf, "# Cavalry benchmark scene: %" PRIu64 " triangles, seed %" PRIu64 "%s%s.\n"
            "# Written by bench/gen_scene; regenerate rather than edit.\n",
            o.triangles, o.seed, o.indirect ? ", indirect (closed room)" : "",
            o.production ? ", production materials and textures" : "");
    if (o.indirect)
        fprintf(sf, "LookAt %.3f %.3f %.3f  0 6 0  0 1 0\n", -0.8 * H, 0.45 * room_h, -0.8 * H);
    else
        fprintf(sf, "LookAt %.3f %.3f %.3f  0 0 0  0 1 0\n", -1.1 * H, 0.55 * H, -1.3 * H);
    fprintf(sf, "Camera \"perspective\" \"float fov\" [ %d ]\n", o.indirect ? 62 : 45);
    fprintf(sf, "Film \"rgb\" \"integer xresolution\" [ %d ] \"integer yresolution\" [ %d ]\n"
            "    \"string filename\" [ \"scene.exr\" ]\n", o.width, o.height);
    fprintf(sf, "Sampler \"zsobol\" \"integer pixelsamples\" [ %d ]\n", o.spp);
    fprintf(sf, "Integrator \"path\" \"integer maxdepth\" [ %d ]\n\n", o.indirect ? 8 : 5);
    fputs("WorldBegin\n\n", sf);
    write_materials(sf);
    if (o.production)
        write_production_materials(sf);

    if (!o.indirect) {
        fputs("LightSource \"distant\" \"point3 from\" [ -0.4 1 -0.25 ] \"point3 to\" [ 0 0 0 ]\n"
              "    \"rgb L\" [ 2.6 2.4 2.1 ]\n"
              "LightSource \"infinite\" \"rgb L\" [ 0.25 0.3 0.4 ]\n\n", sf);
    }

    /* Reserve a share of the budget for the ground (or room), a few lights,
     * and spread the rest over objects with log-uniform sizes. */
    struct mesh m = {0};
    uint64_t total = o.triangles;
    uint64_t ground_min = total / 10;
    uint64_t used = 0;
    int n_files = 0;
    char name[256];

    /* Area lights: small emissive quads (2 triangles each, counted). */
    int n_lights = o.indirect ? 1 : 3;
    for (int l = 0; l < n_lights; l++) {
        mesh_reset(&m, true);
        double s = o.indirect ? 4.0 : rng_range(1.5, 4.0);
        double cx, cy, cz, nx, ny, nz;
        if (o.indirect) {
            /* Lamp near the +x wall facing it; its back emits nothing. */
            cx = H - 3.0, cy = room_h * 0.5, cz = 0, nx = 1, ny = 0, nz = 0;
            uint32_t a = mesh_vertex(&m, cx, cy - s, cz - s, nx, ny, nz);
            uint32_t b = mesh_vertex(&m, cx, cy - s, cz + s, nx, ny, nz);
            uint32_t c = mesh_vertex(&m, cx, cy + s, cz - s, nx, ny, nz);
            uint32_t d = mesh_vertex(&m, cx, cy + s, cz + s, nx, ny, nz);
            /* (b-a) x (c-a) = (0,0,2s) x (0,2s,0) = -x: wind the other way. */
            mesh_tri(&m, a, c, b);
            mesh_tri(&m, b, c, d);
        } else {
            cx = rng_range(-0.6, 0.6) * H, cy = rng_range(12, 22), cz = rng_range(-0.6, 0.6) * H;
            nx = 0, ny = -1, nz = 0;
            uint32_t a = mesh_vertex(&m, cx - s, cy, cz - s, nx, ny, nz);
            uint32_t b = mesh_vertex(&m, cx + s, cy, cz - s, nx, ny, nz);
            uint32_t c = mesh_vertex(&m, cx - s, cy, cz + s, nx, ny, nz);
            uint32_t d = mesh_vertex(&m, cx + s, cy, cz + s, nx, ny, nz);
            /* (b-a) x (c-a) = (2s,0,0) x (0,0,2s) = -y: faces down. */
            mesh_tri(&m, a, b, c);
            mesh_tri(&m, b, d, c);
        }
        snprintf(name, sizeof name, "geometry/light_%02d.ply", l);
        if (!mesh_write_ply(&m, name))
            return 1;
        n_files++;
        used += m.nt;
        double power = o.indirect ? 60.0 : rng_range(15, 40);
        fprintf(sf, "AttributeBegin\n    AreaLightSource \"diffuse\" \"rgb L\" [ %.3f %.3f %.3f ]\n"
                "    Material \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n"
                "    Shape \"plymesh\" \"string filename\" [ \"%s\" ]\nAttributeEnd\n",
                power, power * 0.92, power * 0.8, name);
    }
    if (o.indirect) {
        /* Walls and ceiling of the room: a box seen from inside, shading
         * normals pointing in. The floor is the terrain below. */
        mesh_reset(&m, false);
        shape_cube(&m, 8, false, 0);
        /* Drop the bottom face (-y) so the terrain is the floor: faces are
         * written in the order +x -x +y -y +z -z, 2*64 triangles each. */
        size_t per_face = 2 * 64;
        memmove(m.idx + 3 * 3 * per_face, m.idx + 3 * 4 * per_face,
                2 * per_face * 3 * sizeof(uint32_t));
        m.nt -= per_face;
        struct xform x;
        xform_make(&x, (double[3]){H + 0.5, room_h / 2, H + 0.5}, 0, 0, 0,
                   (double[3]){0, room_h / 2 - 0.5, 0});
        mesh_apply(&m, &x);
        snprintf(name, sizeof name, "geometry/room.ply");
        if (!mesh_write_ply(&m, name))
            return 1;
        n_files++;
        used += m.nt;
        fprintf(sf, "AttributeBegin\n    NamedMaterial \"diffuse_white\"\n"
                "    Shape \"plymesh\" \"string filename\" [ \"%s\" ]\nAttributeEnd\n", name);
    }

    /* Objects: count grows with the budget so that big scenes have more
     * objects as well as finer ones; per-object budgets are log-uniform over
     * two and a half decades. */
    uint64_t obj_budget = total - used - ground_min;
    int n_obj = (int)(sqrt((double)obj_budget) / 3.0);
    if (n_obj < 12)
        n_obj = 12;
    if (n_obj > 6000)
        n_obj = 6000;
    double *w = malloc(sizeof(double) * (size_t)n_obj);
    double wsum = 0;
    for (int i = 0; i < n_obj; i++)
        wsum += (w[i] = exp(rng_range(0, 2.5 * log(10.0))));
    int n_clusters = 3 + (int)(rng_uniform() * 5);
    double clusters[8][3];
    for (int c = 0; c < n_clusters; c++) {
        clusters[c][0] = rng_range(-0.7, 0.7) * H;
        clusters[c][1] = rng_range(-0.7, 0.7) * H;
        clusters[c][2] = rng_range(0.05, 0.18) * H;     /* spread */
    }
    uint64_t kind_tris[K_COUNT] = {0};
    int kind_count[K_COUNT] = {0};
    for (int i = 0; i < n_obj; i++) {
        double budget = (double)obj_budget * w[i] / wsum;
        double pick = rng_uniform();
        enum kind k = pick < 0.28 ? K_SPHERE : pick < 0.5 ? K_BLOB : pick < 0.68 ? K_TORUS
                    : pick < 0.88 ? K_BOX : K_PANEL;
        int n = shape_param(k, budget);
        if (used + shape_tris(k, n) + ground_min > total)
            continue;
        mesh_reset(&m, k != K_BOX && k != K_PANEL);
        switch (k) {
        case K_SPHERE: shape_cube(&m, n, true, 0); break;
        case K_BLOB: shape_cube(&m, n, true, 3 + (int)(rng_uniform() * 5)); break;
        case K_TORUS: shape_torus(&m, 4 * n, n, rng_range(0.15, 0.45)); break;
        default: shape_cube(&m, n, false, 0); break;
        }
        /* Bigger objects get more triangles, but not strictly: scale is
         * half from the budget, half random. */
        double size = 0.25 * pow(budget, 0.18) * exp(rng_gauss() * 0.5);
        if (o.indirect)
            size *= 0.6;
        double sc[3] = {size, size, size};
        if (k == K_BOX)
            sc[0] *= rng_range(0.3, 2.5), sc[1] *= rng_range(0.3, 2.5), sc[2] *= rng_range(0.3, 2.5);
        if (k == K_PANEL)
            sc[0] *= rng_range(1.5, 4.0), sc[1] *= rng_range(1.0, 3.0), sc[2] *= 0.02;
        if (k == K_BLOB)
            sc[1] *= rng_range(0.6, 1.4);
        double px, pz;
        if (rng_uniform() < 0.65) {
            int c = (int)(rng_uniform() * n_clusters);
            px = clusters[c][0] + rng_gauss() * clusters[c][2];
            pz = clusters[c][1] + rng_gauss() * clusters[c][2];
        } else {
            px = rng_range(-0.9, 0.9) * H, pz = rng_range(-0.9, 0.9) * H;
        }
        if (px < -0.95 * H) px = -0.95 * H;
        if (px > 0.95 * H) px = 0.95 * H;
        if (pz < -0.95 * H) pz = -0.95 * H;
        if (pz > 0.95 * H) pz = 0.95 * H;
        bool upright = k == K_PANEL || k == K_BOX;
        struct xform x;
        xform_make(&x, sc, rng_range(0, 2 * M_PI),
                   upright ? rng_range(-0.15, 0.15) : rng_range(-1.2, 1.2),
                   upright ? rng_range(-0.1, 0.1) : rng_range(-1.2, 1.2),
                   (double[3]){px, 0, pz});
        if (o.production)
            mesh_uv_spherical(&m, k == K_PANEL || k == K_BOX ? 2.0 : 1.0 + (double)(rng_next() % 4));
        mesh_apply(&m, &x);
        /* Rest on the ground, some floating above it. */
        double lo, hi;
        mesh_y_range(&m, &lo, &hi);
        double lift = -lo + (rng_uniform() < 0.2 ? rng_range(0.5, 6.0) : 0.0);
        if (o.indirect && hi + lift > room_h - 2)
            lift = room_h - 2 - hi;
        for (size_t v = 0; v < m.nv; v++)
            m.pos[3 * v + 1] += (float)lift;
        snprintf(name, sizeof name, "geometry/%s_%05d.ply", kind_name[k], i);
        if (!mesh_write_ply(&m, name))
            return 1;
        n_files++;
        used += m.nt;
        kind_tris[k] += m.nt;
        kind_count[k]++;
        char prod[32];
        const char *mat;
        if (o.production) {
            snprintf(prod, sizeof prod, "prod_%02d", (int)(rng_next() % N_PROD_MATERIALS));
            mat = prod;
        } else {
            mat = materials[rng_next() % (sizeof materials / sizeof materials[0])];
        }
        fprintf(sf, "AttributeBegin\n    NamedMaterial \"%s\"\n"
                "    Shape \"plymesh\" \"string filename\" [ \"%s\" ]\nAttributeEnd\n", mat, name);
    }
    free(w);

    /* The ground takes the rest so the count is exact. */
    mesh_reset(&m, true);
    shape_ground(&m, total - used, 1.05 * H, o.indirect ? 0.05 : 0.6);
    /* Sink the terrain a little so objects placed at y=0 touch it. */
    for (size_t v = 0; v < m.nv; v++)
        m.pos[3 * v + 1] -= o.indirect ? 0.0f : 0.4f;
    if (o.production)
        mesh_uv_planar(&m, 6.0);
    snprintf(name, sizeof name, "geometry/ground.ply");
    if (!mesh_write_ply(&m, name))
        return 1;
    n_files++;
    used += m.nt;
    fprintf(sf, "AttributeBegin\n    NamedMaterial \"%s\"\n"
            "    Shape \"plymesh\" \"string filename\" [ \"%s\" ]\nAttributeEnd\n",
            o.production ? "prod_00" : o.indirect ? "diffuse_clay" : "diffuse_white", name);

    if (fclose(sf) != 0) {
        fprintf(stderr, "gen_scene: %s: %s\n", scene_path, strerror(errno));
        return 1;
    }
    double secs = elapsed_s(&t0);
    fprintf(stderr, "gen_scene: %s: %" PRIu64 " triangles in %d PLY files, %.1f MB in %.2f s "
            "(%.0f MB/s)\n", scene_path, used, n_files, bytes_written / 1e6, secs,
            bytes_written / 1e6 / (secs > 0 ? secs : 1e-9));
    for (int k = 0; k < K_COUNT; k++)
        fprintf(stderr, "  %-6s %5d objects %12" PRIu64 " triangles\n", kind_name[k],
                kind_count[k], kind_tris[k]);
    free(m.pos);
    free(m.nrm);
    free(m.uv);
    free(m.idx);
    free(ply_buf);
    return used == total ? 0 : 1;
}
