/* color_params.h: what a job asks of the colour stage. Shared by the C API
 * (color.h) and the OpenColorIO shim (ocio.h). */
#ifndef CV_COLOR_PARAMS_H
#define CV_COLOR_PARAMS_H

struct cv_color_params {
    /* OCIO config file. NULL or "": $OCIO, then the config Cavalry ships
     * (configs/cavalry.ocio: from $CAVALRY_DATA_DIR when set, else the copy
     * compiled into the binary). */
    const char *config_path;
    const char *display;   /* NULL or "": the config's default display */
    const char *view;      /* NULL or "": the display's default view */
    /* Comma-separated look names applied in place of the view's own looks;
     * NULL: the view's looks as the config defines them; "": none. */
    const char *look;
    /* Stops, applied in scene-linear before the view (a Raw view too: an
     * asked-for exposure scales the values it passes through). */
    float exposure;
};

#endif
