/* display_encoding.h: what a view's display colour space encodes, as far as
 * Cavalry can tell it from the config (src/color/ocio_spaces.cpp), so that
 * PNGs are tagged with what they hold (src/output/png_write.c) and with
 * nothing where that is unknown. */
#ifndef CV_COLOR_DISPLAY_ENCODING_H
#define CV_COLOR_DISPLAY_ENCODING_H

enum cv_display_encoding {
    CV_DISPLAY_UNKNOWN = 0, /* not one below (a Raw or data view, linear output, a
                             * curve or primaries not recognised): untagged */
    CV_DISPLAY_SRGB,        /* Rec.709 primaries, D65 white, piecewise sRGB curve */
    CV_DISPLAY_P3,          /* P3 primaries, D65 white, piecewise sRGB curve */
    CV_DISPLAY_BT1886,      /* Rec.709 primaries, D65 white, BT.1886 (2.4 power) */
};

/* "sRGB", "Display P3", "BT.1886", "unknown": for logs and tests. */
static inline const char *cv_display_encoding_name(enum cv_display_encoding e)
{
    switch (e) {
    case CV_DISPLAY_SRGB: return "sRGB";
    case CV_DISPLAY_P3: return "Display P3";
    case CV_DISPLAY_BT1886: return "BT.1886";
    default: return "unknown";
    }
}

#endif
