/* key_set.h: a set of strings with a value each (open addressing, linear
 * probing, kept at most half full), for the duplicate checks of the manifest
 * reader: keys of a mapping, job names, outputs. Each lookup costs a
 * constant expected number of string comparisons, so checking n keys is
 * linear in n, where comparing each key with all earlier ones was quadratic
 * (40,000 keys: 800 million comparisons). */
#ifndef CV_MANIFEST_KEY_SET_H
#define CV_MANIFEST_KEY_SET_H

#include <stdbool.h>
#include <stddef.h>

struct cv_key_set {
    struct cv_key_slot {
        const char *key;      /* borrowed; NULL: empty slot */
        size_t hash;
        size_t value;
    } *slots;
    size_t cap, n;            /* cap: 0 or a power of two */
    unsigned long compares;   /* string comparisons made, for the tests */
};

/* Adds key with value unless it is there. Returns true when added; false
 * when present, with its first value in *first (when first is not NULL).
 * The key must outlive the set. A zeroed set is an empty set. */
bool cv_key_set_add(struct cv_key_set *s, const char *key, size_t value, size_t *first);
/* Whether key is in the set. */
bool cv_key_set_has(struct cv_key_set *s, const char *key);
/* Frees the slots; the set is empty again (the count of compares is kept). */
void cv_key_set_clear(struct cv_key_set *s);

#endif
