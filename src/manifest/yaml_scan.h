/* yaml_scan.h: a first pass over a manifest's YAML events, before libyaml
 * builds the document, that holds the text to limits no real manifest comes
 * near: nesting depth, anchors and aliases. A manifest from an untrusted
 * hand can then not make the reader recurse, allocate or (through merge
 * keys over aliases) walk without bound. Linear in the text. */
#ifndef CV_MANIFEST_YAML_SCAN_H
#define CV_MANIFEST_YAML_SCAN_H

#include <stdbool.h>
#include <stddef.h>

#include "manifest/diag.h"

/* Sequences and mappings inside one another (a job's aovs list is at 4). */
#define CV_YAML_MAX_DEPTH 64
/* &name definitions and *name uses in one manifest. */
#define CV_YAML_MAX_ANCHORS 1000
#define CV_YAML_MAX_ALIASES 10000

/* False, with one message at the offending node's line:col, when a limit is
 * passed. A syntax error is left to the document loader, which reports it
 * (true is returned). */
bool cv_yaml_scan(const char *data, size_t len, struct cv_diag *d);

#endif
