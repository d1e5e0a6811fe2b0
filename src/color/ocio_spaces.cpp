/* ocio_spaces.cpp: see ocio_spaces.hpp. The render works in linear Rec.709
 * (what pbrt scenes assume); a config's scene_linear role may be another
 * space (ACEScg), so the display transform starts from the render's space
 * as the config knows it, never from an assumption. */
#include <cmath>
#include <stdexcept>

#include "color/ocio_spaces.hpp"

namespace cv_ocio_spaces {

namespace {

/* Names (and aliases) by which configs call linear Rec.709; OpenColorIO
 * matches them case-insensitively. */
const char *const kLinearRec709Names[] = {
    "lin_rec709", "Linear Rec.709 (sRGB)", "lin_srgb", "Linear sRGB",
    "Utility - Linear - sRGB", "Utility - Linear - Rec.709",
};

/* The space added to a config that has none of its own. */
const char kAddedName[] = "Cavalry render - linear Rec.709";

typedef double Mat3[3][3];

struct Primaries {
    double r[2], g[2], b[2], w[2];  /* CIE xy */
};
const Primaries kRec709 = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};
const Primaries kP3D65 = {{0.680, 0.320}, {0.265, 0.690}, {0.150, 0.060}, {0.3127, 0.3290}};

void inverse(const Mat3 m, Mat3 out)
{
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            out[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
}

void apply(const Mat3 m, const double in[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[i][0] * in[0] + m[i][1] * in[1] + m[i][2] * in[2];
}

/* RGB -> CIE XYZ of primaries p (white at Y = 1). */
void rgb_to_xyz(const Primaries &p, Mat3 out)
{
    const double *xy[3] = {p.r, p.g, p.b};
    Mat3 m, inv;
    for (int c = 0; c < 3; c++) {
        m[0][c] = xy[c][0] / xy[c][1];
        m[1][c] = 1.0;
        m[2][c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
    }
    double w[3] = {p.w[0] / p.w[1], 1.0, (1.0 - p.w[0] - p.w[1]) / p.w[1]}, s[3];
    inverse(m, inv);
    apply(inv, w, s);
    for (int i = 0; i < 3; i++)
        for (int c = 0; c < 3; c++)
            out[i][c] = m[i][c] * s[c];
}

double srgb_curve(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double bt1886_curve(double v)
{
    return std::pow(v, 1.0 / 2.4);
}

struct Encoding {
    cv_display_encoding id;
    const Primaries *primaries;
    double (*curve)(double);
};
const Encoding kEncodings[] = {
    {CV_DISPLAY_SRGB, &kRec709, srgb_curve},
    {CV_DISPLAY_P3, &kP3D65, srgb_curve},
    {CV_DISPLAY_BT1886, &kRec709, bt1886_curve},
};

/* Colours inside both gamuts, away from black, where the curves differ. */
const double kProbes[][3] = {
    {0.18, 0.18, 0.18}, {0.7, 0.2, 0.05}, {0.1, 0.6, 0.3}, {0.05, 0.1, 0.8}, {0.9, 0.85, 0.8},
};
const int kNumProbes = sizeof(kProbes) / sizeof(kProbes[0]);

OCIO::TransformRcPtr builtin(const char *style, bool inverse_dir)
{
    OCIO::BuiltinTransformRcPtr t = OCIO::BuiltinTransform::Create();
    t->setStyle(style);
    t->setDirection(inverse_dir ? OCIO::TRANSFORM_DIR_INVERSE : OCIO::TRANSFORM_DIR_FORWARD);
    return t;
}

/* Linear Rec.709 to ACES2065-1 (Bradford adaptation from D65), and on to
 * CIE XYZ (D65), by OpenColorIO's built-in transforms. */
OCIO::GroupTransformRcPtr rec709_to_aces()
{
    OCIO::GroupTransformRcPtr g = OCIO::GroupTransform::Create();
    g->appendTransform(builtin("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD", true));
    g->appendTransform(builtin("ACEScg_to_ACES2065-1", false));
    return g;
}

OCIO::GroupTransformRcPtr rec709_to_xyz()
{
    OCIO::GroupTransformRcPtr g = rec709_to_aces();
    g->appendTransform(builtin("UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD", false));
    return g;
}

/* The transform from cs to its reference space; nullptr when cs is it. */
OCIO::TransformRcPtr to_reference(const OCIO::ConstColorSpaceRcPtr &cs)
{
    if (OCIO::ConstTransformRcPtr t = cs->getTransform(OCIO::COLORSPACE_DIR_TO_REFERENCE))
        return t->createEditableCopy();
    if (OCIO::ConstTransformRcPtr t = cs->getTransform(OCIO::COLORSPACE_DIR_FROM_REFERENCE)) {
        OCIO::TransformRcPtr e = t->createEditableCopy();
        e->setDirection(OCIO::GetInverseTransformDirection(e->getDirection()));
        return e;
    }
    return nullptr;
}

/* The role's colour space where it is scene-referred and not data. */
OCIO::ConstColorSpaceRcPtr scene_role(const OCIO::ConstConfigRcPtr &config, const char *role)
{
    if (!config->hasRole(role))
        return nullptr;
    OCIO::ConstColorSpaceRcPtr cs = config->getColorSpace(role);
    if (!cs || cs->isData() || cs->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_SCENE)
        return nullptr;
    return cs;
}

void run(const OCIO::ConstProcessorRcPtr &p, const double in[3], double out[3])
{
    float px[3] = {(float)in[0], (float)in[1], (float)in[2]};
    p->getDefaultCPUProcessor()->applyRGB(px);
    for (int c = 0; c < 3; c++)
        out[c] = px[c];
}

/* Whether processors a and b agree on the probes within tol (relative to
 * the larger component). */
bool agree(const OCIO::ConstProcessorRcPtr &a, const OCIO::ConstProcessorRcPtr &b, double tol)
{
    for (int k = 0; k < kNumProbes; k++) {
        double x[3], y[3];
        run(a, kProbes[k], x);
        run(b, kProbes[k], y);
        double m = std::fmax(std::fabs(y[0]), std::fmax(std::fabs(y[1]), std::fabs(y[2])));
        for (int c = 0; c < 3; c++)
            if (!(std::fabs(x[c] - y[c]) <= tol * std::fmax(m, 1e-3)))
                return false;
    }
    return true;
}

RenderSpace added_space(const OCIO::ConstConfigRcPtr &config,
                        const OCIO::ConstColorSpaceRcPtr &interchange,
                        const OCIO::GroupTransformRcPtr &link, const std::string &how,
                        const std::string &source)
{
    if (config->getColorSpace(kAddedName))
        throw SpaceError("colour config " + source + " already has a colour space \"" +
                                 kAddedName + "\", the name Cavalry gives the render's space");
    OCIO::GroupTransformRcPtr g = link;
    if (OCIO::TransformRcPtr t = to_reference(interchange))
        g->appendTransform(t);
    OCIO::ColorSpaceRcPtr cs = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_SCENE);
    cs->setName(kAddedName);
    cs->setTransform(g, OCIO::COLORSPACE_DIR_TO_REFERENCE);
    OCIO::ConfigRcPtr e = config->createEditableCopy();
    e->addColorSpace(cs);
    return RenderSpace{e, kAddedName, how};
}

} // namespace

RenderSpace find_render_space(const OCIO::ConstConfigRcPtr &config, const std::string &source)
{
    OCIO::ConstColorSpaceRcPtr aces = scene_role(config, OCIO::ROLE_INTERCHANGE_SCENE);
    for (const char *name : kLinearRec709Names) {
        OCIO::ConstColorSpaceRcPtr cs = config->getColorSpace(name);
        if (!cs || cs->isData() || cs->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_SCENE)
            continue;
        if (aces && !agree(config->getProcessor(cs->getName(), aces->getName()),
                           OCIO::Config::CreateRaw()->getProcessor(rec709_to_aces()), 1e-4))
            throw SpaceError(
                "colour config " + source + ": colour space \"" + cs->getName() +
                "\" is named as linear Rec.709 but does not convert to the aces_interchange "
                "role's \"" + aces->getName() + "\" as linear Rec.709 does");
        return RenderSpace{config, cs->getName(), std::string("colour space \"") + cs->getName() + "\""};
    }
    if (aces)
        return added_space(config, aces, rec709_to_aces(),
                           std::string("aces_interchange role (\"") + aces->getName() + "\")",
                           source);
    if (OCIO::ConstColorSpaceRcPtr xyz = scene_role(config, OCIO::ROLE_INTERCHANGE_DISPLAY))
        return added_space(config, xyz, rec709_to_xyz(),
                           std::string("cie_xyz_d65_interchange role (\"") + xyz->getName() + "\")",
                           source);
    std::string names;
    for (const char *name : kLinearRec709Names)
        names += std::string(names.empty() ? "\"" : ", \"") + name + "\"";
    throw SpaceError(
        "colour config " + source + " does not say where linear Rec.709, the render's colour "
        "space, lies: it has no aces_interchange role, no scene-referred "
        "cie_xyz_d65_interchange role and no colour space named " + names +
        "; add one of those");
}

cv_display_encoding identify_encoding(const RenderSpace &rs, const char *display,
                                      const char *view)
{
    const OCIO::ConstConfigRcPtr &config = rs.config;
    const char *name = config->getDisplayViewColorSpaceName(display, view);
    OCIO::ConstColorSpaceRcPtr cs = name ? config->getColorSpace(name) : nullptr;
    if (!cs || cs->isData())
        return CV_DISPLAY_UNKNOWN;
    /* where the probes start, and that space's RGB -> XYZ (identity for XYZ) */
    std::string src;
    Mat3 src_to_xyz = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (cs->getReferenceSpaceType() == OCIO::REFERENCE_SPACE_DISPLAY) {
        if (!config->hasRole(OCIO::ROLE_INTERCHANGE_DISPLAY))
            return CV_DISPLAY_UNKNOWN;
        OCIO::ConstColorSpaceRcPtr xyz = config->getColorSpace(OCIO::ROLE_INTERCHANGE_DISPLAY);
        if (!xyz || xyz->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_DISPLAY)
            return CV_DISPLAY_UNKNOWN;
        src = xyz->getName();
    } else {
        src = rs.name;
        rgb_to_xyz(kRec709, src_to_xyz);
    }
    OCIO::ConstCPUProcessorRcPtr p =
        config->getProcessor(src.c_str(), cs->getName())->getDefaultCPUProcessor();
    Mat3 xyz_to_src;
    inverse(src_to_xyz, xyz_to_src);
    for (const Encoding &e : kEncodings) {
        Mat3 m;
        rgb_to_xyz(*e.primaries, m);
        bool all = true;
        for (int k = 0; k < kNumProbes && all; k++) {
            double xyz[3], s[3];
            apply(m, kProbes[k], xyz);
            apply(xyz_to_src, xyz, s);
            float px[3] = {(float)s[0], (float)s[1], (float)s[2]};
            p->applyRGB(px);
            for (int c = 0; c < 3; c++)
                all = all && std::fabs(px[c] - e.curve(kProbes[k][c])) <= 2e-3;
        }
        if (all)
            return e.id;
    }
    return CV_DISPLAY_UNKNOWN;
}

} // namespace cv_ocio_spaces
