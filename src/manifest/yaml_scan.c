/* yaml_scan.c: see yaml_scan.h. */
#include <yaml.h>

#include "manifest/yaml_scan.h"

static const unsigned char *anchor_of(const yaml_event_t *e)
{
    switch (e->type) {
    case YAML_SCALAR_EVENT: return e->data.scalar.anchor;
    case YAML_SEQUENCE_START_EVENT: return e->data.sequence_start.anchor;
    case YAML_MAPPING_START_EVENT: return e->data.mapping_start.anchor;
    default: return NULL;
    }
}

bool cv_yaml_scan(const char *data, size_t len, struct cv_diag *d)
{
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser))
        return true; /* the loader will fail the same way and say so */
    yaml_parser_set_input_string(&parser, (const unsigned char *)data, len);
    unsigned depth = 0, anchors = 0, aliases = 0;
    bool ok = true, more = true;
    while (ok && more) {
        yaml_event_t e;
        if (!yaml_parser_parse(&parser, &e))
            break;
        size_t line = e.start_mark.line + 1, col = e.start_mark.column + 1;
        more = e.type != YAML_STREAM_END_EVENT;
        if (e.type == YAML_SEQUENCE_START_EVENT || e.type == YAML_MAPPING_START_EVENT) {
            if (++depth > CV_YAML_MAX_DEPTH) {
                cv_diag_add(d, line, col, "nested deeper than %d sequences and mappings",
                            CV_YAML_MAX_DEPTH);
                ok = false;
            }
        } else if (e.type == YAML_SEQUENCE_END_EVENT || e.type == YAML_MAPPING_END_EVENT) {
            depth--;
        } else if (e.type == YAML_ALIAS_EVENT && ++aliases > CV_YAML_MAX_ALIASES) {
            cv_diag_add(d, line, col, "more than %d aliases (*name)", CV_YAML_MAX_ALIASES);
            ok = false;
        }
        if (ok && anchor_of(&e) && ++anchors > CV_YAML_MAX_ANCHORS) {
            cv_diag_add(d, line, col, "more than %d anchors (&name)", CV_YAML_MAX_ANCHORS);
            ok = false;
        }
        yaml_event_delete(&e);
    }
    yaml_parser_delete(&parser);
    return ok;
}
