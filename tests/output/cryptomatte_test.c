/* cryptomatte_test.c: MurmurHash3_x86_32 against published values (the
 * Cryptomatte specification's manifest example, Blender's metadata key
 * test, the common "quick brown fox" vector), the float conversion's
 * exponent clamp, the manifest's JSON, and the ranking of (id, weight)
 * pairs merged over a pixel's path slots, on slots made by hand. */
#include <stdlib.h>
#include <string.h>

#include "output/cryptomatte.h"
#include "tests/tap.h"

static uint32_t bits_of(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof(b));
    return b;
}

static uint32_t mm(const char *s)
{
    return cv_murmur3_32(s, strlen(s), 0);
}

/* one slot's words: (id, weight) pairs from CV_MATTE_CRYPTO_OBJECT on */
static void put(uint32_t *w, int rank, uint32_t id, float weight)
{
    w[CV_MATTE_CRYPTO_OBJECT + 2 * rank] = id;
    memcpy(&w[CV_MATTE_CRYPTO_OBJECT + 2 * rank + 1], &weight, sizeof(weight));
}

int main(void)
{
    /* the specification's example manifest gives the float bits */
    tap_ok(bits_of(cv_crypto_id("bunny")) == 0x13851a76u, "bunny -> 13851a76 (specification)");
    tap_ok(bits_of(cv_crypto_id("default")) == 0x42c9679fu, "default -> 42c9679f");
    tap_ok(bits_of(cv_crypto_id("bunny_porcelain_mat")) == 0xb24b26d4u,
           "bunny_porcelain_mat -> b24b26d4");
    tap_ok(mm("The quick brown fox jumps over the lazy dog") == 0x2e4ff723u,
           "quick brown fox -> 2e4ff723");
    tap_ok(mm("") == 0, "empty string, seed 0 -> 0");
    tap_ok(cv_murmur3_32("", 0, 1) == 0x514e28b7u, "empty string, seed 1 -> 514e28b7");
    /* Blender: cryptomatte/c7dbf5e/... for "ViewLayer.CryptoMaterial" */
    tap_ok(mm("ViewLayer.CryptoMaterial") >> 4 == 0xc7dbf5eu, "metadata key c7dbf5e (Blender)");
    /* tails of 1, 2 and 3 bytes */
    tap_ok(mm("a") == 0x3c2569b2u && mm("ab") == 0x9bbfd75fu && mm("abc") == 0xb3dd93fau,
           "tails of 1 to 3 bytes");

    tap_ok(bits_of(cv_crypto_float(0x00000001u)) == 0x00800001u, "exponent 0 becomes 1");
    tap_ok(bits_of(cv_crypto_float(0xff800003u)) == 0xff000003u, "exponent 255 becomes 254");
    tap_ok(bits_of(cv_crypto_float(0x80000000u)) == 0x80800000u, "sign kept");
    tap_ok(bits_of(cv_crypto_float(0x3f800000u)) == 0x3f800000u, "others unchanged");

    const char *names[] = {"b\"q", "a", "b\"q"};
    struct cv_crypto_type t = {.layer = "CryptoObject", .names = names, .n_names = 3,
                               .first_word = CV_MATTE_CRYPTO_OBJECT};
    char *m = cv_crypto_manifest(&t);
    char want[128];
    snprintf(want, sizeof(want), "{\"a\":\"%08x\",\"b\\\"q\":\"%08x\"}",
             bits_of(cv_crypto_id("a")), bits_of(cv_crypto_id("b\"q")));
    tap_ok(strcmp(m, want) == 0, "manifest sorted, escaped, each name once: %s", m);
    free(m);
    char *ids = cv_id_names_json(names, 2);
    tap_ok(strcmp(ids, "{\"1\":\"b\\\"q\",\"2\":\"a\"}") == 0, "ID AOV names: %s", ids);
    free(ids);

    /* two pixels, two slots each (slot s of pixel i at s * 2 + i) */
    enum { STRIDE = CV_MATTE_WORDS_CRYPTO };
    uint32_t words[4 * STRIDE] = {0};
    float weight[4] = {4, 4, 4, 0};
    /* pixel 0: id 2 ("a") 1 + 2, id 1 ("b\"q") 2, id 3 (also "b\"q") 1: the
     * name's two ids are one matte of weight 3, ranked before "a" (3) by
     * its id bits only if they are smaller */
    put(words + 0 * STRIDE, 0, 2, 1);
    put(words + 0 * STRIDE, 1, 1, 2);
    put(words + 2 * STRIDE, 0, 3, 1);
    put(words + 2 * STRIDE, 1, 2, 2);
    /* pixel 1: slot 0 weight 4 with id 2 at 1; slot 1 nothing */
    put(words + 1 * STRIDE, 0, 2, 1);
    struct cv_matte_slots s = {.words = words, .weight = weight, .stride = STRIDE,
                               .slots_per_pixel = 2, .n_pixels = 2};
    float l0[8], l1[8], l2[8];
    float *layers[CV_CRYPTO_LAYERS] = {l0, l1, l2};
    cv_crypto_layers(&s, &t, layers);
    uint32_t a = bits_of(cv_crypto_id("a")), b = bits_of(cv_crypto_id("b\"q"));
    uint32_t first = a < b ? a : b, second = a < b ? b : a;
    tap_ok(bits_of(l0[0]) == first && l0[1] == 3.0f / 8 && bits_of(l0[2]) == second &&
               l0[3] == 3.0f / 8,
           "pixel 0: one name's ids merged; equal coverage ranked by id bits");
    tap_ok(l1[0] == 0 && l1[1] == 0 && l1[2] == 0 && l1[3] == 0 && l2[0] == 0,
           "pixel 0: ranks 2 to 5 empty");
    tap_ok(bits_of(l0[4]) == a && l0[5] == 1.0f / 4 && l0[6] == 0 && l0[7] == 0,
           "pixel 1: coverage over the weight of both slots");
    return tap_done();
}
