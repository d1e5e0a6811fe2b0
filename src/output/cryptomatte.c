/* cryptomatte.c: see cryptomatte.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "output/cryptomatte.h"

static uint32_t rotl32(uint32_t x, int r)
{
    return (x << r) | (x >> (32 - r));
}

/* Austin Appleby's public-domain algorithm: 4-byte blocks read
 * little-endian, a tail of up to 3 bytes, then the finalising mix. */
uint32_t cv_murmur3_32(const void *key, size_t len, uint32_t seed)
{
    const uint8_t *p = key;
    const uint32_t c1 = 0xcc9e2d51u, c2 = 0x1b873593u;
    uint32_t h = seed;
    size_t blocks = len / 4;
    for (size_t i = 0; i < blocks; i++) {
        const uint8_t *b = p + 4 * i;
        uint32_t k = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                     (uint32_t)b[3] << 24;
        k *= c1;
        k = rotl32(k, 15);
        k *= c2;
        h ^= k;
        h = rotl32(h, 13);
        h = h * 5 + 0xe6546b64u;
    }
    const uint8_t *tail = p + 4 * blocks;
    uint32_t k = 0;
    switch (len & 3) {
    case 3: k ^= (uint32_t)tail[2] << 16; /* fall through */
    case 2: k ^= (uint32_t)tail[1] << 8;  /* fall through */
    case 1:
        k ^= tail[0];
        k *= c1;
        k = rotl32(k, 15);
        k *= c2;
        h ^= k;
    }
    h ^= (uint32_t)len;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

/* The exponent is clamped to [1, 254]: no denormal, infinity or NaN,
 * which some tools flush or treat apart. */
static uint32_t float_bits(uint32_t hash)
{
    uint32_t exponent = hash >> 23 & 255u;
    if (exponent == 0)
        exponent = 1;
    else if (exponent == 255)
        exponent = 254;
    return (hash & 0x807fffffu) | exponent << 23;
}

float cv_crypto_float(uint32_t hash)
{
    uint32_t bits = float_bits(hash);
    float f;
    memcpy(&f, &bits, sizeof(f));
    return f;
}

float cv_crypto_id(const char *name)
{
    return cv_crypto_float(cv_murmur3_32(name, strlen(name), 0));
}

struct pair {
    uint32_t bits;   /* the id's float bits; 0: none */
    float w;
};

/* most coverage first; ties by id bits, so the order never depends on
 * the order the samples came in */
static int by_weight(const void *a, const void *b)
{
    const struct pair *x = a, *y = b;
    if (x->w != y->w)
        return x->w > y->w ? -1 : 1;
    return (x->bits > y->bits) - (x->bits < y->bits);
}

void cv_crypto_layers(const struct cv_matte_slots *m, const struct cv_crypto_type *t,
                      float *layers[CV_CRYPTO_LAYERS])
{
    uint32_t n = m->n_pixels, k = m->slots_per_pixel;
    uint32_t *bits = cv_xmalloc((t->n_names + 1) * sizeof(uint32_t));
    bits[0] = 0;
    for (uint32_t i = 0; i < t->n_names; i++) {
        const char *name = t->names[i];
        bits[i + 1] = float_bits(cv_murmur3_32(name, strlen(name), 0));
    }
    struct pair *p = cv_xmalloc((size_t)k * CV_MATTE_RANK * sizeof(*p));
    for (uint32_t i = 0; i < n; i++) {
        size_t np = 0;
        float total = 0;
        for (uint32_t s = 0; s < k; s++) {
            size_t slot = (size_t)s * n + i;
            const uint32_t *w = m->words + slot * m->stride + t->first_word;
            total += m->weight[slot];
            for (uint32_t r = 0; r < CV_MATTE_RANK; r++) {
                uint32_t id = w[2 * r];
                float weight;
                memcpy(&weight, &w[2 * r + 1], sizeof(weight));
                if (id == 0 || id > t->n_names)
                    break;
                size_t j = 0;
                while (j < np && p[j].bits != bits[id])
                    j++;
                if (j == np)
                    p[np++] = (struct pair){bits[id], 0};
                p[j].w += weight;
            }
        }
        qsort(p, np, sizeof(*p), by_weight);
        float inv = total != 0 ? 1 / total : 0; /* signed filter weights */
        for (uint32_t r = 0; r < CV_MATTE_RANK; r++) {
            float id = 0, cov = 0;
            if (r < np) {
                memcpy(&id, &p[r].bits, sizeof(id));
                cov = p[r].w * inv;
            }
            float *px = layers[r / 2] + (size_t)i * 4 + (r % 2) * 2;
            px[0] = id;
            px[1] = cov;
        }
    }
    free(p);
    free(bits);
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* s as a JSON string body: quotes, backslashes and control characters
 * escaped; other bytes (UTF-8) as they are */
static void json_string(char **out, size_t *len, size_t *cap, const char *s)
{
    for (; *s; s++) {
        char buf[8];
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            snprintf(buf, sizeof(buf), "\\%c", c);
        else if (c < 0x20)
            snprintf(buf, sizeof(buf), "\\u%04x", c);
        else
            snprintf(buf, sizeof(buf), "%c", c);
        size_t bl = strlen(buf);
        *out = cv_xgrow(*out, cap, *len + bl + 1, 1);
        memcpy(*out + *len, buf, bl + 1);
        *len += bl;
    }
}

static void append(char **out, size_t *len, size_t *cap, const char *s)
{
    size_t sl = strlen(s);
    *out = cv_xgrow(*out, cap, *len + sl + 1, 1);
    memcpy(*out + *len, s, sl + 1);
    *len += sl;
}

char *cv_crypto_manifest(const struct cv_crypto_type *t)
{
    const char **sorted = cv_xmalloc((t->n_names ? t->n_names : 1) * sizeof(*sorted));
    for (uint32_t i = 0; i < t->n_names; i++)
        sorted[i] = t->names[i];
    qsort(sorted, t->n_names, sizeof(*sorted), by_name);
    char *out = NULL;
    size_t len = 0, cap = 0;
    append(&out, &len, &cap, "{");
    for (uint32_t i = 0; i < t->n_names; i++) {
        if (i > 0 && strcmp(sorted[i], sorted[i - 1]) == 0)
            continue;
        char hex[16];
        snprintf(hex, sizeof(hex), "%08x",
                 float_bits(cv_murmur3_32(sorted[i], strlen(sorted[i]), 0)));
        append(&out, &len, &cap, len > 1 ? ",\"" : "\"");
        json_string(&out, &len, &cap, sorted[i]);
        append(&out, &len, &cap, "\":\"");
        append(&out, &len, &cap, hex);
        append(&out, &len, &cap, "\"");
    }
    append(&out, &len, &cap, "}");
    free(sorted);
    return out;
}

char *cv_id_names_json(const char *const *names, uint32_t n)
{
    char *out = NULL;
    size_t len = 0, cap = 0;
    append(&out, &len, &cap, "{");
    for (uint32_t i = 0; i < n; i++) {
        char id[32];
        snprintf(id, sizeof(id), "%s\"%u\":\"", i ? "," : "", i + 1);
        append(&out, &len, &cap, id);
        json_string(&out, &len, &cap, names[i]);
        append(&out, &len, &cap, "\"");
    }
    append(&out, &len, &cap, "}");
    return out;
}

void cv_crypto_metadata(struct cv_metadata *meta, const struct cv_crypto_type *t)
{
    char key[16], attr[64];
    snprintf(key, sizeof(key), "%08x", cv_murmur3_32(t->layer, strlen(t->layer), 0));
    key[7] = '\0';
    static const char *const fields[][2] = {
        {"hash", "MurmurHash3_32"},
        {"conversion", "uint32_to_float32"},
    };
    snprintf(attr, sizeof(attr), "cryptomatte/%s/name", key);
    cv_metadata_set_string(meta, attr, t->layer);
    for (size_t i = 0; i < CV_ARRAY_SIZE(fields); i++) {
        snprintf(attr, sizeof(attr), "cryptomatte/%s/%s", key, fields[i][0]);
        cv_metadata_set_string(meta, attr, fields[i][1]);
    }
    char *manifest = cv_crypto_manifest(t);
    snprintf(attr, sizeof(attr), "cryptomatte/%s/manifest", key);
    cv_metadata_set_string(meta, attr, manifest);
    free(manifest);
}
