// ocio_shim.cpp: OpenColorIO's C++ API behind the C header ocio.h. Every
// entry point catches all exceptions and turns them into cv_error messages,
// so nothing C++ escapes into the C program.
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>

extern "C" {
#include "base/error.h"
#include "base/mem.h"
}
#include "color/ocio.h"
#include "color/ocio_spaces.hpp"

namespace OCIO = OCIO_NAMESPACE;

namespace {

// Our own failures (bad names, missing files), told apart from OpenColorIO's
// so that theirs can be prefixed with where they came from.
struct Failure : std::runtime_error {
    explicit Failure(const std::string &m) : std::runtime_error(m) {}
};

bool file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

std::string join(const std::vector<std::string> &v)
{
    std::string s;
    for (size_t i = 0; i < v.size(); i++)
        s += (i ? ", \"" : "\"") + v[i] + "\"";
    return v.empty() ? std::string("(none)") : s;
}

OCIO::ConstConfigRcPtr load_config(const char *path, std::string &source)
{
    const char *file = cv_ocio_config_file(path);
    if (!file) {
        source = "shipped cavalry.ocio";
        std::istringstream text(cv_ocio_shipped_config);
        return OCIO::Config::CreateFromStream(text);
    }
    source = file;
    /* a built-in config's URI: OpenColorIO 2.2 and later resolve it, older
     * ones fail with their own message */
    bool uri = std::strncmp(file, "ocio://", 7) == 0;
    if (!uri && !file_exists(file)) {
        if (path && path[0])
            throw Failure("colour config \"" + source + "\": no such file");
        throw Failure("$OCIO names the colour config \"" + source +
                      "\", which does not exist (unset OCIO to use Cavalry's shipped config)");
    }
    return OCIO::Config::CreateFromFile(file);
}

OCIO::ConstConfigRcPtr open_config(const char *path, std::string &source)
{
    try {
        OCIO::ConstConfigRcPtr config = load_config(path, source);
        config->validate();
        return config;
    } catch (const Failure &) {
        throw;
    } catch (const std::exception &e) {
        throw Failure("colour config " + source + ": " + e.what());
    }
}

std::vector<std::string> display_names(const OCIO::ConstConfigRcPtr &config)
{
    std::vector<std::string> v;
    for (int i = 0; i < config->getNumDisplays(); i++)
        v.push_back(config->getDisplay(i));
    return v;
}

std::vector<std::string> view_names(const OCIO::ConstConfigRcPtr &config, const char *display)
{
    std::vector<std::string> v;
    for (int i = 0; i < config->getNumViews(display); i++)
        v.push_back(config->getView(display, i));
    return v;
}

bool contains(const std::vector<std::string> &v, const char *name)
{
    for (const std::string &s : v)
        if (s == name)
            return true;
    return false;
}

// Checks each name of a "a, +b, -c" / "a:b" look list against the config.
void check_looks(const OCIO::ConstConfigRcPtr &config, const std::string &looks,
                 const std::string &source)
{
    std::vector<std::string> valid;
    for (int i = 0; i < config->getNumLooks(); i++)
        valid.push_back(config->getLookNameByIndex(i));
    size_t pos = 0;
    while (pos <= looks.size()) {
        size_t end = looks.find_first_of(",:", pos);
        if (end == std::string::npos)
            end = looks.size();
        std::string name = looks.substr(pos, end - pos);
        size_t a = name.find_first_not_of(" \t");
        size_t b = name.find_last_not_of(" \t");
        name = a == std::string::npos ? "" : name.substr(a, b - a + 1);
        if (!name.empty() && (name[0] == '+' || name[0] == '-'))
            name.erase(0, 1);
        if (!name.empty() && !config->getLook(name.c_str()))
            throw Failure("unknown look \"" + name + "\" in colour config " + source +
                          "; looks: " + join(valid));
        pos = end + 1;
    }
}

char *dup(const std::string &s)
{
    return cv_xstrdup(s.c_str());
}

} // namespace

struct cv_ocio {
    OCIO::ConstConfigRcPtr config;
    OCIO::ConstProcessorRcPtr processor;
    OCIO::ConstCPUProcessorRcPtr cpu;
    OCIO::ConstGPUProcessorRcPtr gpu;
    OCIO::GpuShaderDescRcPtr shader;
    std::string description, source;
    std::string render_space;  // how the render's space was found
    cv_display_encoding encoding = CV_DISPLAY_UNKNOWN;
};

#define CV_OCIO_TRY try {
#define CV_OCIO_CATCH(err, ctx)                                               \
    }                                                                          \
    catch (const Failure &e) {                                                 \
        return cv_fail(err, "%s", e.what());                                   \
    }                                                                          \
    catch (const std::exception &e) {                                          \
        return cv_fail(err, "OpenColorIO: %s: %s", ctx, e.what());            \
    }                                                                          \
    catch (...) {                                                              \
        return cv_fail(err, "OpenColorIO: %s: unknown exception", ctx);       \
    }

extern "C" bool cv_ocio_create(const struct cv_color_params *p, struct cv_ocio **out,
                               struct cv_error *err)
{
    *out = nullptr;
    cv_ocio *o = new (std::nothrow) cv_ocio;
    if (!o)
        return cv_fail(err, "out of memory");
    CV_OCIO_TRY
        if (!std::isfinite(p->exposure))
            throw Failure("colour exposure must be a finite number of stops");
        o->config = open_config(p->config_path, o->source);
        const OCIO::ConstConfigRcPtr &config = o->config;
        if (!config->getColorSpace(OCIO::ROLE_SCENE_LINEAR))
            throw Failure("colour config " + o->source + " has no scene_linear role");
        // The render is in linear Rec.709, which scene_linear need not be:
        // the transform starts from that space as the config knows it.
        cv_ocio_spaces::RenderSpace rs;
        try {
            rs = cv_ocio_spaces::find_render_space(config, o->source);
        } catch (const cv_ocio_spaces::SpaceError &e) {
            throw Failure(e.what());
        }
        o->config = rs.config;  // a copy with the space added, where it had none
        o->render_space = rs.how;

        std::vector<std::string> displays = display_names(config);
        std::string display = p->display && p->display[0] ? p->display
                                                           : config->getDefaultDisplay();
        if (!contains(displays, display.c_str()))
            throw Failure("unknown display \"" + display + "\" in colour config " + o->source +
                          "; displays: " + join(displays));
        std::vector<std::string> views = view_names(config, display.c_str());
        std::string view = p->view && p->view[0] ? p->view
                                                 : config->getDefaultView(display.c_str());
        if (!contains(views, view.c_str()))
            throw Failure("unknown view \"" + view + "\" for display \"" + display +
                          "\" in colour config " + o->source + "; views: " + join(views));

        OCIO::DisplayViewTransformRcPtr dvt = OCIO::DisplayViewTransform::Create();
        dvt->setSrc(rs.name.c_str());
        dvt->setDisplay(display.c_str());
        dvt->setView(view.c_str());
        OCIO::LegacyViewingPipelineRcPtr pipe = OCIO::LegacyViewingPipeline::Create();
        pipe->setDisplayViewTransform(dvt);
        // Exposure as a dynamic property: the GPU shader reads it from a
        // uniform, so one compiled pass could serve any exposure.
        OCIO::ExposureContrastTransformRcPtr ec = OCIO::ExposureContrastTransform::Create();
        ec->setStyle(OCIO::EXPOSURE_CONTRAST_LINEAR);
        ec->setExposure(p->exposure);
        ec->makeExposureDynamic();
        pipe->setLinearCC(ec);
        if (p->look) {
            check_looks(config, p->look, o->source);
            pipe->setLooksOverrideEnabled(true);
            pipe->setLooksOverride(p->look);
        }
        o->processor = pipe->getProcessor(config);
        o->encoding = cv_ocio_spaces::identify_encoding(rs, display.c_str(), view.c_str());
        // The oracle: no approximations beyond lossless op folding.
        o->cpu = o->processor->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                                        OCIO::OPTIMIZATION_LOSSLESS);

        o->description = display + " / " + view;
        if (p->look && p->look[0])
            o->description += std::string(" / look: ") + p->look;
        if (p->exposure != 0.0f) {
            char ev[48];
            snprintf(ev, sizeof(ev), " / exposure %+g EV", (double)p->exposure);
            o->description += ev;
        }
        *out = o;
        return true;
    }
    catch (const Failure &e) {
        delete o;
        return cv_fail(err, "%s", e.what());
    }
    catch (const std::exception &e) {
        delete o;
        return cv_fail(err, "OpenColorIO: building the display transform: %s", e.what());
    }
    catch (...) {
        delete o;
        return cv_fail(err, "OpenColorIO: building the display transform: unknown exception");
    }
}

extern "C" void cv_ocio_destroy(struct cv_ocio **ocio)
{
    if (!ocio || !*ocio)
        return;
    try {
        delete *ocio;
    } catch (...) {
    }
    *ocio = nullptr;
}

extern "C" const char *cv_ocio_description(const struct cv_ocio *ocio)
{
    return ocio->description.c_str();
}

extern "C" const char *cv_ocio_config_source(const struct cv_ocio *ocio)
{
    return ocio->source.c_str();
}

extern "C" const char *cv_ocio_render_space(const struct cv_ocio *ocio)
{
    return ocio->render_space.c_str();
}

extern "C" enum cv_display_encoding cv_ocio_display_encoding(const struct cv_ocio *ocio)
{
    return ocio->encoding;
}

extern "C" bool cv_ocio_apply_cpu(const struct cv_ocio *ocio, float *rgba, size_t n,
                                  struct cv_error *err)
{
    CV_OCIO_TRY
        // Rows of at most 2^20 pixels keep the sizes within long.
        const size_t row = (size_t)1 << 20;
        for (size_t at = 0; at < n; at += row) {
            size_t k = n - at < row ? n - at : row;
            OCIO::PackedImageDesc img(rgba + 4 * at, (long)k, 1, 4);
            ocio->cpu->apply(img);
        }
        return true;
    CV_OCIO_CATCH(err, "applying the CPU processor")
}

extern "C" bool cv_ocio_gpu_extract(struct cv_ocio *ocio, const char *function_name,
                                    struct cv_error *err)
{
    CV_OCIO_TRY
        ocio->shader = OCIO::GpuShaderDesc::CreateShaderDesc();
        // OCIO 2.1 offers no GLSL 4.5 dialect; 4.0 compiles in a 450 shader.
        ocio->shader->setLanguage(OCIO::GPU_LANGUAGE_GLSL_4_0);
        ocio->shader->setFunctionName(function_name);
        ocio->shader->setResourcePrefix(function_name);
        // Lossless folding only: the default level may replace op chains
        // with baked LUTs, which would move the GPU away from the oracle.
        ocio->gpu = ocio->processor->getOptimizedGPUProcessor(OCIO::OPTIMIZATION_LOSSLESS);
        ocio->gpu->extractGpuShaderInfo(ocio->shader);
        return true;
    CV_OCIO_CATCH(err, "generating the GPU shader")
}

extern "C" const char *cv_ocio_gpu_source(const struct cv_ocio *ocio)
{
    return ocio->shader ? ocio->shader->getShaderText() : "";
}

extern "C" unsigned cv_ocio_gpu_texture_count(const struct cv_ocio *ocio)
{
    return ocio->shader ? ocio->shader->getNumTextures() + ocio->shader->getNum3DTextures() : 0;
}

extern "C" bool cv_ocio_gpu_texture(const struct cv_ocio *ocio, unsigned i,
                                    struct cv_ocio_texture *t, struct cv_error *err)
{
    CV_OCIO_TRY
        *t = cv_ocio_texture{};
        const char *tex_name = nullptr, *sampler = nullptr;
        OCIO::Interpolation interp = OCIO::INTERP_DEFAULT;
        unsigned n1 = ocio->shader->getNumTextures();
        if (i < n1) {
            unsigned w = 0, h = 0;
            OCIO::GpuShaderDesc::TextureType channel = OCIO::GpuShaderDesc::TEXTURE_RGB_CHANNEL;
            ocio->shader->getTexture(i, tex_name, sampler, w, h, channel, interp);
            ocio->shader->getTextureValues(i, t->values);
            // OCIO 2.1 declares a sampler2D when a 1D LUT is folded into rows.
            t->dims = h > 1 ? 2 : 1;
            t->width = w;
            t->height = h ? h : 1;
            t->depth = 1;
            t->channels = channel == OCIO::GpuShaderDesc::TEXTURE_RED_CHANNEL ? 1 : 3;
        } else {
            unsigned edge = 0;
            ocio->shader->get3DTexture(i - n1, tex_name, sampler, edge, interp);
            ocio->shader->get3DTextureValues(i - n1, t->values);
            t->dims = 3;
            t->width = t->height = t->depth = edge;
            t->channels = 3;
        }
        t->sampler = sampler;
        t->linear = interp != OCIO::INTERP_NEAREST;
        return true;
    CV_OCIO_CATCH(err, "reading a GPU texture")
}

extern "C" unsigned cv_ocio_gpu_uniform_count(const struct cv_ocio *ocio)
{
    return ocio->shader ? ocio->shader->getNumUniforms() : 0;
}

extern "C" bool cv_ocio_gpu_uniform(const struct cv_ocio *ocio, unsigned i,
                                    struct cv_ocio_uniform *u, struct cv_error *err)
{
    CV_OCIO_TRY
        *u = cv_ocio_uniform{};
        OCIO::GpuShaderDesc::UniformData data;
        u->name = ocio->shader->getUniform(i, data);
        switch (data.m_type) {
        case OCIO::UNIFORM_DOUBLE:
            u->type = CV_OCIO_UNIFORM_FLOAT;
            u->v[0] = (float)data.m_getDouble();
            break;
        case OCIO::UNIFORM_BOOL:
            u->type = CV_OCIO_UNIFORM_BOOL;
            u->b = data.m_getBool();
            break;
        case OCIO::UNIFORM_FLOAT3: {
            u->type = CV_OCIO_UNIFORM_FLOAT3;
            const OCIO::Float3 &f = data.m_getFloat3();
            u->v[0] = f[0];
            u->v[1] = f[1];
            u->v[2] = f[2];
            break;
        }
        case OCIO::UNIFORM_VECTOR_FLOAT:
            u->type = CV_OCIO_UNIFORM_FLOAT_ARRAY;
            u->count = data.m_vectorFloat.m_getSize();
            u->fv = data.m_vectorFloat.m_getVector();
            break;
        case OCIO::UNIFORM_VECTOR_INT:
            u->type = CV_OCIO_UNIFORM_INT_ARRAY;
            u->count = data.m_vectorInt.m_getSize();
            u->iv = data.m_vectorInt.m_getVector();
            break;
        default:
            throw Failure(std::string("OpenColorIO uniform \"") + (u->name ? u->name : "?") +
                          "\" has a type Cavalry does not know");
        }
        return true;
    CV_OCIO_CATCH(err, "reading a GPU uniform")
}

extern "C" bool cv_ocio_list_views(const char *config_path, char ***names, size_t *n_pairs,
                                   struct cv_error *err)
{
    *names = nullptr;
    *n_pairs = 0;
    CV_OCIO_TRY
        std::string source;
        OCIO::ConstConfigRcPtr config = open_config(config_path, source);
        std::vector<std::string> flat;
        for (const std::string &d : display_names(config))
            for (const std::string &v : view_names(config, d.c_str())) {
                flat.push_back(d);
                flat.push_back(v);
            }
        char **out = (char **)cv_xcalloc(flat.size() + 1, sizeof(char *));
        for (size_t i = 0; i < flat.size(); i++)
            out[i] = dup(flat[i]);
        *names = out;
        *n_pairs = flat.size() / 2;
        return true;
    CV_OCIO_CATCH(err, "listing views")
}

extern "C" void cv_ocio_free_names(char ***names)
{
    if (!names || !*names)
        return;
    for (char **n = *names; *n; n++)
        free(*n);
    free(*names);
    *names = nullptr;
}

extern "C" const char *cv_ocio_config_file(const char *config_path)
{
    if (config_path && config_path[0])
        return config_path;
    const char *env = getenv("OCIO");
    if (env && env[0])
        return env;
    static std::string data;
    const char *dir = getenv("CAVALRY_DATA_DIR");
    if (dir && dir[0]) {
        data = std::string(dir) + "/configs/cavalry.ocio";
        if (file_exists(data.c_str()))
            return data.c_str();
    }
    return nullptr;
}
