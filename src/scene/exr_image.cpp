/* exr_image.cpp: see exr_image.h. */
#include <cstdlib>
#include <cstring>
#include <exception>

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfRgbaFile.h>

extern "C" {
#include "base/error.h"
#include "base/mem.h"
}
#include "scene/exr_image.h"

namespace {

/* Luminance-chroma: OpenEXR's RGBA interface decodes it (in half). */
void read_yc(const char *path, const Imath::Box2i &dw, long w, float *px)
{
    Imf::RgbaInputFile in(path);
    long h = dw.max.y - dw.min.y + 1;
    Imf::Rgba *tmp = static_cast<Imf::Rgba *>(cv_xmalloc((size_t)w * h * sizeof(Imf::Rgba)));
    try {
        in.setFrameBuffer(tmp - dw.min.x - (long)dw.min.y * w, 1, (size_t)w);
        in.readPixels(dw.min.y, dw.max.y);
    } catch (...) {
        free(tmp);
        throw;
    }
    for (long i = 0; i < w * h; i++) {
        px[4 * i + 0] = tmp[i].r;
        px[4 * i + 1] = tmp[i].g;
        px[4 * i + 2] = tmp[i].b;
        px[4 * i + 3] = tmp[i].a;
    }
    free(tmp);
}

}  // namespace

extern "C" bool cv_exr_image_load(const char *path, long max_dim, long max_pixels, float **rgba,
                                  int *width, int *height, struct cv_error *err)
{
    *rgba = NULL;
    float *px = NULL;
    try {
        Imf::InputFile in(path);
        const Imf::Header &hdr = in.header();
        Imath::Box2i dw = hdr.dataWindow();
        long w = (long)dw.max.x - dw.min.x + 1, h = (long)dw.max.y - dw.min.y + 1;
        if (w <= 0 || h <= 0 || w > max_dim || h > max_dim || w * h > max_pixels)
            return cv_fail(err, "%s: bad EXR data window", path);
        px = static_cast<float *>(cv_xmalloc((size_t)w * h * 4 * sizeof(float)));
        const Imf::ChannelList &ch = hdr.channels();
        bool rgb = ch.findChannel("R") || ch.findChannel("G") || ch.findChannel("B");
        bool y = ch.findChannel("Y") != NULL;
        if (!rgb && y && (ch.findChannel("RY") || ch.findChannel("BY"))) {
            read_yc(path, dw, w, px);
        } else {
            /* Y alone goes into R and is copied to G and B below */
            const char *names[4] = {rgb ? "R" : "Y", "G", "B", "A"};
            size_t xs = 4 * sizeof(float), ys = (size_t)w * xs;
            Imf::FrameBuffer fb;
            for (int c = 0; c < 4; c++)
                if (rgb || c == 0 || c == 3)
                    fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, px + c, dw, xs, ys, 1, 1,
                                                         c == 3 ? 1.0 : 0.0));
            in.setFrameBuffer(fb);
            in.readPixels(dw.min.y, dw.max.y);
            if (!rgb)
                for (long i = 0; i < w * h; i++)
                    px[4 * i + 1] = px[4 * i + 2] = px[4 * i];
        }
        *rgba = px;
        *width = (int)w;
        *height = (int)h;
        return true;
    } catch (const std::exception &e) {
        free(px);
        return cv_fail(err, "%s: %s", path, e.what());
    } catch (...) {
        free(px);
        return cv_fail(err, "%s: unknown OpenEXR error", path);
    }
}
