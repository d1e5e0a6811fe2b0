/* enums.c: see enums.h. The order of each table is the order of its enum. */
#include <string.h>

#include "base/mem.h"
#include "manifest/enums.h"

static const char *const integrators[] = {"path", "rlpath", "volpath", "bdpt"};
static const char *const compressions[] = {"zip", "none", "zips", "piz", "rle", "dwaa", "dwab"};
/* the manifest's order, which its messages print */
static const char *const manifest_compressions[] = {"none", "zip", "piz", "dwaa", "dwab"};
static const char *const guides[] = {"all", "indirect"};
static const char *const methods[] = {"qlearn", "sdtree"};
static const char *const filters[] = {"none", "spatial", "directional", "both"};
static const char *const formats[] = {"exr", "png"};
static const char *const aovs[] = {"albedo",    "normal",        "depth",          "object_id",
                                   "material_id", "crypto_object", "crypto_material"};

_Static_assert(CV_ARRAY_SIZE(integrators) == CV_INTEGRATOR_COUNT, "one name per integrator");
_Static_assert(CV_ARRAY_SIZE(guides) == CV_RL_GUIDE_COUNT, "one name per rlpath guide");
_Static_assert(CV_ARRAY_SIZE(methods) == CV_RL_METHOD_COUNT, "one name per rlpath method");
_Static_assert(CV_ARRAY_SIZE(filters) == CV_RL_FILTER_COUNT, "one name per rlpath filter");
_Static_assert(CV_ARRAY_SIZE(compressions) == CV_EXR_COMPRESSION_COUNT,
               "one name per EXR compression");

const struct cv_names cv_integrator_names = {integrators, CV_ARRAY_SIZE(integrators)};
const struct cv_names cv_exr_compression_names = {compressions, CV_ARRAY_SIZE(compressions)};
const struct cv_names cv_manifest_compression_names = {manifest_compressions,
                                                       CV_ARRAY_SIZE(manifest_compressions)};
const struct cv_names cv_rl_guide_names = {guides, CV_ARRAY_SIZE(guides)};
const struct cv_names cv_rl_method_names = {methods, CV_ARRAY_SIZE(methods)};
const struct cv_names cv_rl_filter_names = {filters, CV_ARRAY_SIZE(filters)};
const struct cv_names cv_format_names = {formats, CV_ARRAY_SIZE(formats)};
const struct cv_names cv_aov_names = {aovs, CV_ARRAY_SIZE(aovs)};

const char *cv_name_of(const struct cv_names *t, unsigned v)
{
    return v < t->count ? t->names[v] : NULL;
}

const char *cv_name_of_bit(const struct cv_names *t, unsigned bit)
{
    for (unsigned i = 0; i < t->count; i++)
        if (bit == 1u << i)
            return t->names[i];
    return NULL;
}

int cv_name_find(const struct cv_names *t, const char *name)
{
    for (size_t i = 0; i < t->count; i++)
        if (strcmp(t->names[i], name) == 0)
            return (int)i;
    return -1;
}

const char *cv_integrator_name(enum cv_integrator integrator)
{
    return cv_name_of(&cv_integrator_names, (unsigned)integrator);
}

const char *cv_exr_compression_name(enum cv_exr_compression c)
{
    return cv_name_of(&cv_exr_compression_names, (unsigned)c);
}

const char *cv_format_ext(unsigned format_bit)
{
    return cv_name_of_bit(&cv_format_names, format_bit);
}

const char *cv_aov_name(unsigned aov_bit)
{
    return cv_name_of_bit(&cv_aov_names, aov_bit);
}
