/* dump.h: a canonical, deterministic text summary of a flat scene (counts,
 * bounds, camera, settings, materials, textures, lights, a geometry
 * checksum, warnings) for `cavalry-batch --dump-scene` and for diffing.
 * Numbers are printed with %.6g so that rounding noise below float
 * precision does not show. */
#ifndef CV_SCENE_DUMP_H
#define CV_SCENE_DUMP_H

#include <stdio.h>

#include "scene/scene.h"

void cv_scene_dump(const struct cv_scene *scene, FILE *out);

#endif
