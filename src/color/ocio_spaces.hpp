/* ocio_spaces.hpp: where the render's colours lie in an OpenColorIO config,
 * and what a view's display colour space encodes (C++ only, for
 * ocio_shim.cpp; see ocio_spaces.cpp). */
#ifndef CV_COLOR_OCIO_SPACES_HPP
#define CV_COLOR_OCIO_SPACES_HPP

#include <stdexcept>
#include <string>

#include <OpenColorIO/OpenColorIO.h>

#include "color/display_encoding.h"

namespace cv_ocio_spaces {

namespace OCIO = OCIO_NAMESPACE;

/* A config that does not say where the render's space lies (or says it
 * wrongly): the message names the config. */
struct SpaceError : std::runtime_error {
    explicit SpaceError(const std::string &m) : std::runtime_error(m) {}
};

/* The colour space of the render (linear Rec.709 primaries, D65 white) in
 * a config: `config` is the config to build processors from (a copy with
 * the space added where the config has none of its own), `name` the
 * space's name there, `how` how it was found (for logs). */
struct RenderSpace {
    OCIO::ConstConfigRcPtr config;
    std::string name;
    std::string how;
};

/* Looks for it in this order:
 * 1. a colour space named (or aliased) as one of kLinearRec709Names, which
 *    must, where the config has an aces_interchange role, convert to it as
 *    linear Rec.709 does;
 * 2. the aces_interchange role (ACES2065-1): a space is added that converts
 *    linear Rec.709 to it with OpenColorIO's built-in transforms;
 * 3. a scene-referred cie_xyz_d65_interchange role (CIE XYZ, D65), likewise.
 * Throws SpaceError, naming `source`, when none applies or a named
 * space converts otherwise. */
RenderSpace find_render_space(const OCIO::ConstConfigRcPtr &config, const std::string &source);

/* The encoding of the colour space that (display, view) ends in, found by
 * converting probe colours into it from display-referred CIE XYZ (the
 * cie_xyz_d65_interchange role) or, for a scene-referred space, from the
 * render's space, and comparing with each known encoding.
 * CV_DISPLAY_UNKNOWN for data spaces and whatever matches none. */
cv_display_encoding identify_encoding(const RenderSpace &rs, const char *display,
                                      const char *view);

} // namespace cv_ocio_spaces

#endif
