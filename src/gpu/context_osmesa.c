/* context_osmesa.c: the OSMesa backend, last resort where EGL offers nothing.
 *
 * libepoxy resolves a GL function on first call by asking which window
 * system context is current (GLX or EGL) and aborts when it finds neither,
 * as under OSMesa. Its dispatch pointers (epoxy_glFoo) are public and
 * writable, so after making the OSMesa context current we point every GL
 * function Cavalry calls at OSMesaGetProcAddress's answer. The list of those
 * functions is generated at build time from the sources (gl_functions.h, by
 * src/gpu/gl_functions.sh), so a newly used function cannot be forgotten.
 *
 * libOSMesa is opened at run time (dlopen), not linked: Mesa 25.1 dropped
 * it, and GPU servers should not need Mesa's software stack to start. */
#include "config.h"

#ifdef HAVE_OSMESA
#include <dlfcn.h>
#include <stdlib.h>

#include <epoxy/gl.h>
#include <GL/osmesa.h>

#include "base/log.h"
#include "base/mem.h"
#include "gpu/context_platform.h"

struct osmesa_api {
    OSMesaContext (*create_context_attribs)(const int *attrib_list, OSMesaContext share);
    GLboolean (*make_current)(OSMesaContext ctx, void *buffer, GLenum type, GLsizei w, GLsizei h);
    OSMESAproc (*get_proc_address)(const char *name);
    void (*destroy_context)(OSMesaContext ctx);
};

struct osmesa_platform {
    void *library;
    struct osmesa_api api;
    OSMesaContext context;
    unsigned char pixel[4]; /* OSMesa needs a colour buffer to be current */
};

static void osmesa_destroy(void *p)
{
    struct osmesa_platform *os = p;
    if (!os)
        return;
    if (os->context)
        os->api.destroy_context(os->context);
    if (os->library)
        dlclose(os->library);
    free(os);
}

static bool load_library(struct osmesa_platform *os, struct cv_error *err)
{
    static const char *const names[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"};
    for (size_t i = 0; i < CV_ARRAY_SIZE(names) && !os->library; i++)
        os->library = dlopen(names[i], RTLD_NOW | RTLD_LOCAL);
    if (!os->library)
        return cv_fail(err, "OSMesa is not installed (%s; Debian: libosmesa6)",
                       dlerror());
    struct {
        const char *name;
        void **slot;
    } syms[] = {
        {"OSMesaCreateContextAttribs", (void **)&os->api.create_context_attribs},
        {"OSMesaMakeCurrent", (void **)&os->api.make_current},
        {"OSMesaGetProcAddress", (void **)&os->api.get_proc_address},
        {"OSMesaDestroyContext", (void **)&os->api.destroy_context},
    };
    for (size_t i = 0; i < CV_ARRAY_SIZE(syms); i++) {
        *syms[i].slot = dlsym(os->library, syms[i].name);
        if (!*syms[i].slot)
            return cv_fail(err, "libOSMesa lacks %s", syms[i].name);
    }
    return true;
}

static bool install_dispatch(const struct osmesa_api *api, struct cv_error *err)
{
#define CV_GL_FN(name)                                                        \
    do {                                                                      \
        OSMESAproc fn = api->get_proc_address(#name);                         \
        if (!fn)                                                              \
            return cv_fail(err, "OSMesa lacks %s", #name);                    \
        epoxy_##name = (__typeof__(epoxy_##name))(void (*)(void))fn;                        \
    } while (0);
#include "gpu/gl_functions.h"
#undef CV_GL_FN
    return true;
}

bool cv_osmesa_open(bool debug, struct cv_gpu *gpu, struct cv_error *err)
{
    static const int versions[][2] = {{4, 6}, {4, 5}, {4, 3}};
    struct osmesa_platform *os = cv_xcalloc(1, sizeof(*os));
    gpu->platform = os;
    gpu->platform_destroy = osmesa_destroy;
    if (!load_library(os, err))
        return false;
    for (size_t v = 0; v < CV_ARRAY_SIZE(versions) && !os->context; v++) {
        const int attr[] = {
            OSMESA_FORMAT, OSMESA_RGBA,
            OSMESA_DEPTH_BITS, 0,
            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
            OSMESA_CONTEXT_MAJOR_VERSION, versions[v][0],
            OSMESA_CONTEXT_MINOR_VERSION, versions[v][1],
            0,
        };
        os->context = os->api.create_context_attribs(attr, NULL);
    }
    if (!os->context)
        return cv_fail(err, "OSMesa: no OpenGL 4.3+ core context");
    if (!os->api.make_current(os->context, os->pixel, GL_UNSIGNED_BYTE, 1, 1))
        return cv_fail(err, "OSMesaMakeCurrent failed");
    if (!install_dispatch(&os->api, err))
        return false;
    (void)debug; /* OSMesa contexts take no debug flag; KHR_debug still works */
    snprintf(gpu->info.backend, sizeof(gpu->info.backend), "osmesa");
    snprintf(gpu->info.device, sizeof(gpu->info.device), "software");
    gpu->info.device_index = -1;
    return true;
}
#endif
