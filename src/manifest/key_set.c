/* key_set.c: see key_set.h. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "manifest/key_set.h"

/* FNV-1a: short keys, no adversary worth a keyed hash (a manifest is
 * trusted by whoever renders it, and the worst case is still only slow). */
static size_t hash_of(const char *key)
{
    uint64_t h = 1469598103934665603u;
    for (const unsigned char *c = (const unsigned char *)key; *c; c++) {
        h ^= *c;
        h *= 1099511628211u;
    }
    return (size_t)h;
}

/* The slot holding key, or the empty slot where it would go. */
static struct cv_key_slot *find(struct cv_key_set *s, const char *key, size_t h)
{
    size_t mask = s->cap - 1;
    for (size_t i = h & mask;; i = (i + 1) & mask) {
        struct cv_key_slot *slot = &s->slots[i];
        if (!slot->key)
            return slot;
        if (slot->hash == h) {
            s->compares++;
            if (!strcmp(slot->key, key))
                return slot;
        }
    }
}

static void grow(struct cv_key_set *s)
{
    struct cv_key_set bigger = {.cap = s->cap ? s->cap * 2 : 16, .n = s->n,
                                .compares = s->compares};
    bigger.slots = cv_xcalloc(bigger.cap, sizeof(*bigger.slots));
    for (size_t i = 0; i < s->cap; i++) {
        if (!s->slots[i].key)
            continue;
        /* distinct keys: only the empty slot is wanted, no comparison */
        size_t mask = bigger.cap - 1, j = s->slots[i].hash & mask;
        while (bigger.slots[j].key)
            j = (j + 1) & mask;
        bigger.slots[j] = s->slots[i];
    }
    free(s->slots);
    *s = bigger;
}

bool cv_key_set_add(struct cv_key_set *s, const char *key, size_t value, size_t *first)
{
    if (2 * (s->n + 1) > s->cap)
        grow(s);
    size_t h = hash_of(key);
    struct cv_key_slot *slot = find(s, key, h);
    if (slot->key) {
        if (first)
            *first = slot->value;
        return false;
    }
    *slot = (struct cv_key_slot){.key = key, .hash = h, .value = value};
    s->n++;
    return true;
}

bool cv_key_set_has(struct cv_key_set *s, const char *key)
{
    return s->cap && find(s, key, hash_of(key))->key != NULL;
}

void cv_key_set_clear(struct cv_key_set *s)
{
    free(s->slots);
    s->slots = NULL;
    s->cap = s->n = 0;
}
