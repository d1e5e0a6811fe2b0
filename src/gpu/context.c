/* context.c: choosing a backend and device, filling cv_gpu_info, and
 * routing KHR_debug messages into the log. */
#include "config.h"

#include <stdlib.h>
#include <string.h>
#ifdef __SANITIZE_ADDRESS__
#include <dlfcn.h>
#include <stdio.h>
#endif

#include <epoxy/gl.h>

#include "base/log.h"
#include "base/mem.h"
#include "gpu/buffer_pool.h"
#include "gpu/context_platform.h"
#include "gpu/program.h"

#define CV_MAX_CANDIDATES 40

bool cv_gl_has_extension(const char *name)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && strcmp(e, name) == 0)
            return true;
    }
    return false;
}

static void GLAPIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity,
                                      GLsizei length, const GLchar *message, const void *user)
{
    (void)length;
    (void)user;
    enum cv_log_level level = CV_LOG_DEBUG;
    /* Compiler messages come back mapped to glsl/<file>:<line> in the error
     * of cv_program_get; the raw copy is only for debugging. */
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER)
        level = CV_LOG_DEBUG;
    /* NVIDIA reports each read-back as a "performance warning"; they are
     * deliberate (once per pass at most). */
    else if (type == GL_DEBUG_TYPE_PERFORMANCE && severity != GL_DEBUG_SEVERITY_HIGH)
        level = CV_LOG_DEBUG;
    else if (severity == GL_DEBUG_SEVERITY_HIGH || type == GL_DEBUG_TYPE_ERROR)
        level = CV_LOG_ERROR;
    else if (severity == GL_DEBUG_SEVERITY_MEDIUM)
        level = CV_LOG_WARN;
    cv_log(level, "GL debug (id %u): %s", id, message);
}

static void fill_info(struct cv_gpu_info *info)
{
    const char *s;
    s = (const char *)glGetString(GL_VENDOR);
    snprintf(info->vendor, sizeof(info->vendor), "%s", s ? s : "?");
    s = (const char *)glGetString(GL_RENDERER);
    snprintf(info->renderer, sizeof(info->renderer), "%s", s ? s : "?");
    s = (const char *)glGetString(GL_VERSION);
    snprintf(info->version, sizeof(info->version), "%s", s ? s : "?");
    glGetIntegerv(GL_MAJOR_VERSION, &info->gl_major);
    glGetIntegerv(GL_MINOR_VERSION, &info->gl_minor);
    info->software |= strstr(info->renderer, "llvmpipe") || strstr(info->renderer, "softpipe") ||
                      strstr(info->renderer, "lavapipe");
    glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &info->max_compute_ssbo_blocks);
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &info->max_ssbo_bindings);
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &info->max_workgroup_invocations);
    GLint64 bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
    info->max_ssbo_bytes = bytes;
    bytes = 0;
    glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &bytes);
    info->max_texture_buffer_texels = bytes;
    glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &info->max_compute_texture_units);
    info->has_int64 = cv_gl_has_extension("GL_ARB_gpu_shader_int64");
    info->has_shader_ballot = cv_gl_has_extension("GL_KHR_shader_subgroup") ||
                              cv_gl_has_extension("GL_ARB_shader_ballot");
    info->has_nvx_memory_info = cv_gl_has_extension("GL_NVX_gpu_memory_info");
}

static void enable_debug_output(void)
{
    if (!cv_gl_has_extension("GL_KHR_debug"))
        return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, NULL);
    /* Notifications (buffer placement and the like) are noise at info level. */
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, NULL,
                          cv_log_get_level() >= CV_LOG_DEBUG);
}

/* The device that serves when none was asked for: CUDA id 0 where the driver
 * tells (honours CUDA_VISIBLE_DEVICES, and so Slurm/Kubernetes binding), else
 * the first hardware device, else the first software one or surfaceless. */
static int default_candidate(const struct cv_gpu_candidate *c, int n)
{
    for (int i = 0; i < n; i++)
        if (c[i].cuda_id == 0)
            return i;
    for (int i = 0; i < n; i++)
        if (c[i].index >= 0 && !c[i].software)
            return i;
    return n > 0 ? 0 : -1;
}

static int wanted_candidate(const struct cv_gpu_params *p, const struct cv_gpu_candidate *c,
                            int n)
{
    if (p->gpu_index < 0)
        return default_candidate(c, n);
    for (int i = 0; i < n; i++)
        if (c[i].index == p->gpu_index)
            return i;
    return -1;
}

static bool open_candidate(const struct cv_gpu_candidate *cand, bool debug, struct cv_gpu **out,
                           struct cv_error *err)
{
    struct cv_gpu *gpu = cv_xcalloc(1, sizeof(*gpu));
    gpu->info.software = cand->software;
    bool ok = cv_egl_open(cand, debug, gpu, err);
    if (!ok) {
        cv_gpu_destroy(&gpu);
        return false;
    }
    *out = gpu;
    return true;
}

/* LeakSanitizer (--enable-asan) finds live heap blocks through the globals
 * of loaded objects. EGL unloads Mesa's driver with the context, and what
 * the driver still held then is reported as leaked from an "<unknown
 * module>" (128 bytes once it has handled a program binary): noise that
 * would hide a leak of ours. So sanitizer builds pin every shared object
 * loaded once a context is open (RTLD_NOLOAD loads nothing new). */
static void pin_loaded_objects(void)
{
#ifdef __SANITIZE_ADDRESS__
    FILE *maps = fopen("/proc/self/maps", "r");
    char line[4096], last[4096] = "";
    while (maps && fgets(line, sizeof line, maps)) {
        char *path = strchr(line, '/');
        if (!path || !strstr(path, ".so"))
            continue;
        path[strcspn(path, "\n")] = '\0';
        if (strcmp(path, last) == 0)
            continue;
        snprintf(last, sizeof last, "%s", path);
        dlopen(path, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    }
    if (maps)
        fclose(maps);
#endif
}

static bool finish(struct cv_gpu *gpu, struct cv_gpu **out, struct cv_error *err)
{
    pin_loaded_objects();
    fill_info(&gpu->info);
    if (gpu->info.gl_major * 10 + gpu->info.gl_minor < 43) {
        cv_fail(err, "%s offers OpenGL %d.%d; Cavalry needs 4.3 or later", gpu->info.renderer,
                gpu->info.gl_major, gpu->info.gl_minor);
        cv_gpu_destroy(&gpu);
        return false;
    }
    enable_debug_output();
    gpu->programs = cv_program_cache_create();
    gpu->scratch = cv_buffer_pool_create();
    char index[24] = "";  /* tells apart the GPUs of a multi-GPU batch */
    if (gpu->info.device_index >= 0)
        snprintf(index, sizeof(index), " %d", gpu->info.device_index);
    cv_info("GPU: %s (%s, OpenGL %s, %s%s)", gpu->info.renderer, gpu->info.vendor,
            gpu->info.version, gpu->info.backend, index);
    *out = gpu;
    return true;
}

bool cv_gpu_create(const struct cv_gpu_params *params, struct cv_gpu **out, struct cv_error *err)
{
    struct cv_gpu *gpu = NULL;
    if (params->backend != CV_BACKEND_OSMESA) {
        struct cv_gpu_candidate cands[CV_MAX_CANDIDATES];
        int n = cv_egl_candidates(cands, CV_MAX_CANDIDATES);
        int want = wanted_candidate(params, cands, n);
        if (params->gpu_index >= 0 && want < 0)
            return cv_fail(err, "no GPU with index %d (see --list-gpus)", params->gpu_index);
        if (want >= 0) {
            if (open_candidate(&cands[want], params->debug, &gpu, err))
                return finish(gpu, out, err);
            if (params->gpu_index >= 0)
                return false;
            cv_warn("EGL device %s: %s", cands[want].device, err ? err->msg : "failed");
            /* Whatever else EGL offers, in order. */
            for (int i = 0; i < n; i++) {
                if (i != want && open_candidate(&cands[i], params->debug, &gpu, err))
                    return finish(gpu, out, err);
            }
        }
        if (params->backend == CV_BACKEND_EGL)
            return n ? false : cv_fail(err, "EGL offers no device and no surfaceless platform");
    }
#ifdef HAVE_OSMESA
    gpu = cv_xcalloc(1, sizeof(*gpu));
    gpu->info.software = true;
    if (!cv_osmesa_open(params->debug, gpu, err)) {
        cv_gpu_destroy(&gpu);
        return false;
    }
    return finish(gpu, out, err);
#else
    return cv_fail(err, params->backend == CV_BACKEND_OSMESA
                            ? "this build has no OSMesa backend (configure --with-osmesa)"
                            : "no usable GPU: EGL found nothing and this build has no OSMesa");
#endif
}

void cv_gpu_destroy(struct cv_gpu **gpu)
{
    if (!gpu || !*gpu)
        return;
    cv_buffer_pool_destroy(&(*gpu)->scratch);
    cv_program_cache_destroy(&(*gpu)->programs);
    if ((*gpu)->platform_destroy)
        (*gpu)->platform_destroy((*gpu)->platform);
    free(*gpu);
    *gpu = NULL;
}

int cv_gpu_all_devices(const struct cv_gpu_params *params, int *out, int max)
{
    struct cv_gpu_candidate cands[CV_MAX_CANDIDATES];
    if (params->backend == CV_BACKEND_OSMESA)
        return 0;
    int n = cv_egl_candidates(cands, CV_MAX_CANDIDATES), found = 0;
    /* by CUDA id: insertion into out, few devices */
    for (int i = 0; i < n; i++) {
        if (cands[i].index < 0 || cands[i].cuda_id < 0 || found == max)
            continue;
        int at = found++;
        while (at > 0 && cands[out[at - 1]].cuda_id > cands[i].cuda_id) {
            out[at] = out[at - 1];
            at--;
        }
        out[at] = i;
    }
    if (!found)
        for (int i = 0; i < n && found < max; i++)
            if (cands[i].index >= 0 && !cands[i].software)
                out[found++] = i;
    for (int i = 0; i < found; i++)
        out[i] = cands[out[i]].index;
    return found;
}

bool cv_gpu_list(const struct cv_gpu_params *params, FILE *out, struct cv_error *err)
{
    struct cv_gpu_candidate cands[CV_MAX_CANDIDATES] = {{0}}; /* n may be 0 */
    int n = params->backend == CV_BACKEND_OSMESA ? 0 : cv_egl_candidates(cands, CV_MAX_CANDIDATES);
    int want = wanted_candidate(params, cands, n);
    int listed = 0;
    for (int i = 0; i < n; i++) {
        struct cv_gpu *gpu = NULL;
        struct cv_error e = {{0}};
        char idx[16];
        if (cands[i].index >= 0)
            snprintf(idx, sizeof(idx), "%d", cands[i].index);
        else
            snprintf(idx, sizeof(idx), "-");
        if (!open_candidate(&cands[i], false, &gpu, &e)) {
            fprintf(out, "  %-3s %-22s unusable: %s\n", idx, cands[i].device, e.msg);
            continue;
        }
        pin_loaded_objects();
        fill_info(&gpu->info);
        fprintf(out, "%c %-3s %-22s %s | %s | OpenGL %s%s\n", i == want ? '*' : ' ', idx,
                cands[i].device[0] ? cands[i].device : "-", gpu->info.vendor, gpu->info.renderer,
                gpu->info.version, cands[i].cuda_id >= 0 ? " | CUDA device" : "");
        if (cands[i].cuda_id >= 0)
            fprintf(out, "      CUDA id %d\n", cands[i].cuda_id);
        cv_gpu_destroy(&gpu);
        listed++;
    }
#ifdef HAVE_OSMESA
    if (params->backend != CV_BACKEND_EGL) {
        fprintf(out, "%c %-3s %-22s OSMesa (--backend=osmesa)\n",
                (want < 0 || params->backend == CV_BACKEND_OSMESA) ? '*' : ' ', "-", "software");
        listed++;
    }
#endif
    if (!listed)
        return cv_fail(err, "no GPU device found (EGL devices: %d)", n);
    return true;
}
