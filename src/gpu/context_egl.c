/* context_egl.c: the EGL backend. Devices come from EGL_EXT_device_
 * enumeration; a context is made current with no surface (surfaceless
 * contexts are core in EGL 1.5 through EGL_KHR_surfaceless_context). */
#include <stdlib.h>
#include <string.h>

#include <epoxy/egl.h>

#include "base/log.h"
#include "base/mem.h"
#include "gpu/context_platform.h"
#include "gpu/program_disk_cache.h"

#define CV_EGL_KIND_DEVICE 0
#define CV_EGL_KIND_SURFACELESS 1
#define CV_EGL_MAX_DEVICES 32

struct egl_platform {
    EGLDisplay display;
    EGLContext context;
};

static bool has_word(const char *list, const char *word)
{
    size_t n = strlen(word);
    for (const char *p = list; p && (p = strstr(p, word)); p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    }
    return false;
}

static const char *client_extensions(void)
{
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    return ext ? ext : "";
}

static int query_devices(EGLDeviceEXT *devices, int max)
{
    const char *ext = client_extensions();
    if (!has_word(ext, "EGL_EXT_device_enumeration") && !has_word(ext, "EGL_EXT_device_base"))
        return 0;
    EGLint n = 0;
    if (!eglQueryDevicesEXT(max, devices, &n))
        return 0;
    return n;
}

int cv_egl_candidates(struct cv_gpu_candidate *out, int max)
{
    /* The first EGL call of every path that opens a device: the driver
     * reads its cache's place when loaded. */
    cv_program_disk_cache_place_driver_cache();
    EGLDeviceEXT devices[CV_EGL_MAX_DEVICES];
    int n_dev = query_devices(devices, CV_EGL_MAX_DEVICES);
    int n = 0;
    bool platform_device = has_word(client_extensions(), "EGL_EXT_platform_device");
    for (int i = 0; platform_device && i < n_dev && n < max; i++) {
        struct cv_gpu_candidate *c = &out[n++];
        memset(c, 0, sizeof(*c));
        c->index = i;
        c->kind = CV_EGL_KIND_DEVICE;
        c->cuda_id = -1;
        const char *dext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        c->software = dext && has_word(dext, "EGL_MESA_device_software");
        const char *node = NULL;
        if (dext && has_word(dext, "EGL_EXT_device_drm"))
            node = eglQueryDeviceStringEXT(devices[i], EGL_DRM_DEVICE_FILE_EXT);
        snprintf(c->device, sizeof(c->device), "%s", node ? node : c->software ? "software" : "");
        EGLAttrib cuda = -1;
        if (dext && has_word(dext, "EGL_NV_device_cuda") &&
            eglQueryDeviceAttribEXT(devices[i], EGL_CUDA_DEVICE_NV, &cuda))
            c->cuda_id = (int)cuda;
    }
    if (n < max && has_word(client_extensions(), "EGL_MESA_platform_surfaceless")) {
        struct cv_gpu_candidate *c = &out[n++];
        memset(c, 0, sizeof(*c));
        c->index = -1;
        c->kind = CV_EGL_KIND_SURFACELESS;
        c->cuda_id = -1;
        snprintf(c->device, sizeof(c->device), "surfaceless");
    }
    return n;
}

static void egl_destroy(void *p)
{
    struct egl_platform *egl = p;
    if (!egl)
        return;
    if (egl->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (egl->context != EGL_NO_CONTEXT)
            eglDestroyContext(egl->display, egl->context);
        eglTerminate(egl->display);
    }
    free(egl);
}

/* GL 4.6, then 4.5, then 4.3 core; robust (reset notification) first. */
static EGLContext create_context(EGLDisplay dpy, EGLConfig cfg, bool debug, bool *robust)
{
    static const int versions[][2] = {{4, 6}, {4, 5}, {4, 3}};
    for (int r = 1; r >= 0; r--) {
        for (size_t v = 0; v < CV_ARRAY_SIZE(versions); v++) {
            EGLint attr[16], k = 0;
            attr[k++] = EGL_CONTEXT_MAJOR_VERSION;
            attr[k++] = versions[v][0];
            attr[k++] = EGL_CONTEXT_MINOR_VERSION;
            attr[k++] = versions[v][1];
            attr[k++] = EGL_CONTEXT_OPENGL_PROFILE_MASK;
            attr[k++] = EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT;
            if (r) {
                attr[k++] = EGL_CONTEXT_OPENGL_ROBUST_ACCESS;
                attr[k++] = EGL_TRUE;
                attr[k++] = EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY;
                attr[k++] = EGL_LOSE_CONTEXT_ON_RESET;
            }
            if (debug) {
                attr[k++] = EGL_CONTEXT_OPENGL_DEBUG;
                attr[k++] = EGL_TRUE;
            }
            attr[k++] = EGL_NONE;
            EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, attr);
            if (ctx != EGL_NO_CONTEXT) {
                *robust = r;
                return ctx;
            }
        }
    }
    return EGL_NO_CONTEXT;
}

bool cv_egl_open(const struct cv_gpu_candidate *cand, bool debug, struct cv_gpu *gpu,
                 struct cv_error *err)
{
    struct egl_platform *egl = cv_xcalloc(1, sizeof(*egl));
    egl->display = EGL_NO_DISPLAY;
    egl->context = EGL_NO_CONTEXT;
    gpu->platform = egl;
    gpu->platform_destroy = egl_destroy;

    if (cand->kind == CV_EGL_KIND_DEVICE) {
        EGLDeviceEXT devices[CV_EGL_MAX_DEVICES];
        int n = query_devices(devices, CV_EGL_MAX_DEVICES);
        if (cand->index >= n)
            return cv_fail(err, "EGL device %d is gone", cand->index);
        egl->display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[cand->index], NULL);
        snprintf(gpu->info.backend, sizeof(gpu->info.backend), "egl-device");
    } else {
        egl->display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        snprintf(gpu->info.backend, sizeof(gpu->info.backend), "egl-surfaceless");
    }
    if (egl->display == EGL_NO_DISPLAY)
        return cv_fail(err, "eglGetPlatformDisplay failed (EGL error 0x%x)", eglGetError());
    EGLint major, minor;
    if (!eglInitialize(egl->display, &major, &minor)) {
        EGLint e = eglGetError();
        egl->display = EGL_NO_DISPLAY;
        return cv_fail(err, "eglInitialize failed (EGL error 0x%x)", e);
    }
    if (!eglBindAPI(EGL_OPENGL_API))
        return cv_fail(err, "eglBindAPI(EGL_OPENGL_API) failed: this EGL has no desktop OpenGL");

    const char *dext = eglQueryString(egl->display, EGL_EXTENSIONS);
    EGLConfig cfg = (EGLConfig)0; /* EGL_NO_CONFIG_KHR */
    if (!has_word(dext, "EGL_KHR_no_config_context")) {
        static const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                      EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(egl->display, want, &cfg, 1, &n) || n < 1)
            return cv_fail(err, "no EGL config renders desktop OpenGL without a surface");
    }
    if (!has_word(dext, "EGL_KHR_surfaceless_context"))
        return cv_fail(err, "EGL display lacks EGL_KHR_surfaceless_context");

    bool robust = false;
    egl->context = create_context(egl->display, cfg, debug, &robust);
    if (egl->context == EGL_NO_CONTEXT)
        return cv_fail(err, "no OpenGL 4.3+ core context on this EGL display (EGL error 0x%x)",
                       eglGetError());
    if (!eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl->context))
        return cv_fail(err, "eglMakeCurrent failed (EGL error 0x%x)", eglGetError());
    gpu->info.robust = robust;
    gpu->info.device_index = cand->index;
    snprintf(gpu->info.device, sizeof(gpu->info.device), "%s", cand->device);
    cv_debug("EGL %d.%d, %s", major, minor, gpu->info.backend);
    return true;
}
