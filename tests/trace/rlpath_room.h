/* rlpath_room.h: the test rooms of the rlpath tests and benchmark: a closed
 * room split by a partition that stops short of the ceiling, the lamp on
 * one side, so that most of the other side is lit indirectly; and the same
 * room with a black-backed lamp, a rough metal panel (not guided: sampled by
 * its BSDF and learning from one-sample targets) and coated panels (guided,
 * with a glossy coat); and a room open to the camera. */
#ifndef CV_TESTS_TRACE_RLPATH_ROOM_H
#define CV_TESTS_TRACE_RLPATH_ROOM_H

/* The pieces both rooms share: camera and film, the lamp (its light
 * and its shape), the walls and the partition. */
#define RLPATH_ROOM_VIEW \
    "LookAt 0.9 -0.3 0.9  0.4 -0.4 -1  0 1 0\n" \
    "Camera \"perspective\" \"float fov\" [ 60 ]\n" \
    "Sampler \"independent\" \"integer pixelsamples\" [ 16 ]\n" \
    "Integrator \"path\" \"integer maxdepth\" [ 5 ]\n" \
    "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n" \
    "  \"string filename\" \"room.exr\"\n" \
    "PixelFilter \"box\"\n" \
    "WorldBegin\n"
#define RLPATH_ROOM_LIGHT \
    "AttributeBegin\n" \
    "  AreaLightSource \"diffuse\" \"rgb L\" [ 20 20 20 ]\n"
#define RLPATH_ROOM_LAMP \
    "  Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n" \
    "    \"point3 P\" [ -0.8 0.9 -0.3  -0.2 0.9 -0.3  -0.2 0.9 0.3  -0.8 0.9 0.3 ]\n" \
    "AttributeEnd\n"
#define RLPATH_ROOM_WALLS \
    "Material \"diffuse\" \"rgb reflectance\" [ 0.7 0.7 0.7 ]\n" \
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3  4 6 5 4 7 6  0 3 7 0 7 4\n" \
    "    1 5 6 1 6 2  0 4 5 0 5 1  3 2 6 3 6 7 ]\n" \
    "  \"point3 P\" [ -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1 ]\n" \
    "Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.3 0.2 ]\n" \
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n" \
    "  \"point3 P\" [ 0 -1 -1  0 -1 1  0 0.5 1  0 0.5 -1 ]\n"

static const char rlpath_room[] = RLPATH_ROOM_VIEW RLPATH_ROOM_LIGHT RLPATH_ROOM_LAMP
    RLPATH_ROOM_WALLS;

/* The room without the wall the camera faces, nor the partition: many
 * rays leave the scene. */
static const char rlpath_room_open[] =
    RLPATH_ROOM_VIEW RLPATH_ROOM_LIGHT RLPATH_ROOM_LAMP
    "Material \"diffuse\" \"rgb reflectance\" [ 0.7 0.7 0.7 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 4 6 5 4 7 6  0 3 7 0 7 4\n"
    "    1 5 6 1 6 2  0 4 5 0 5 1  3 2 6 3 6 7 ]\n"
    "  \"point3 P\" [ -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1 ]\n";

static const char rlpath_room_glossy[] =
    RLPATH_ROOM_VIEW RLPATH_ROOM_LIGHT
    "  Material \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n"
    RLPATH_ROOM_LAMP RLPATH_ROOM_WALLS
    "Material \"conductor\" \"float roughness\" [ 0.2 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ -0.9 -1 0.2  -0.3 -1 0.6  -0.3 0.2 0.6  -0.9 0.2 0.2 ]\n"
    "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.8 0.75 0.62 ] \"float roughness\" [ 0.05 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ 0.99 -1 -0.8  0.99 -1 0.8  0.99 0.4 0.8  0.99 0.4 -0.8 ]\n"
    "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.08 0.15 0.55 ] \"float roughness\" [ 0.2 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ -0.9 -0.99 -0.9  0.9 -0.99 -0.9  0.9 -0.99 0.9  -0.9 -0.99 0.9 ]\n";

/* A room lit from a lamp in the ceiling, open to it everywhere (light
 * sampling does most of the work: little noise), with a lobe of each kind
 * the guide must leave to the BSDF or share with it: a floor of
 * smooth-coated diffuse (a delta coat over a guided base), a mirror, a
 * rough conductor (not guided) and a coated conductor with a smooth coat
 * over a rough base. */
static const char rlpath_room_lobes[] =
    "LookAt 0.3 0.6 0.95  -0.1 -0.7 -0.5  0 1 0\n"
    "Camera \"perspective\" \"float fov\" [ 70 ]\n"
    "Sampler \"independent\" \"integer pixelsamples\" [ 16 ]\n"
    "Integrator \"path\" \"integer maxdepth\" [ 5 ]\n"
    "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
    "  \"string filename\" \"lobes.exr\"\n"
    "PixelFilter \"box\"\n"
    "WorldBegin\n"
    "AttributeBegin\n"
    "  AreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\n"
    "  Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "    \"point3 P\" [ -0.5 0.99 -0.5  0.5 0.99 -0.5  0.5 0.99 0.5  -0.5 0.99 0.5 ]\n"
    "AttributeEnd\n"
    "Material \"diffuse\" \"rgb reflectance\" [ 0.6 0.6 0.6 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3  4 6 5 4 7 6  0 3 7 0 7 4\n"
    "    1 5 6 1 6 2  0 4 5 0 5 1  3 2 6 3 6 7 ]\n"
    "  \"point3 P\" [ -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1 ]\n"
    "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.6 0.5 0.4 ] \"float roughness\" [ 0 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ -0.95 -0.99 -0.95  0.95 -0.99 -0.95  0.95 -0.99 0.95  -0.95 -0.99 0.95 ]\n"
    "Material \"conductor\" \"float roughness\" [ 0 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ -0.99 -0.8 -0.8  -0.99 0.3 -0.8  -0.99 0.3 0.2  -0.99 -0.8 0.2 ]\n"
    "Material \"conductor\" \"float roughness\" [ 0.2 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ -0.8 -0.9 -0.99  -0.1 -0.9 -0.99  -0.1 0.2 -0.99  -0.8 0.2 -0.99 ]\n"
    "Material \"coatedconductor\" \"float interface.roughness\" [ 0 ] \"float conductor.roughness\" [ 0.4 ]\n"
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ 0.1 -0.9 -0.99  0.8 -0.9 -0.99  0.8 0.2 -0.99  0.1 0.2 -0.99 ]\n";

#endif
