/* scene_tree.h: a pbrt scene loaded, a GL context opened and the
 * renderer's triangle tree built over the scene's static triangles, as
 * cavalry-batch builds it: the set-up the traversal benchmarks (bvh_work,
 * rt_probe) share. */
#ifndef CV_BENCH_SCENE_TREE_H
#define CV_BENCH_SCENE_TREE_H

#include <epoxy/gl.h>

#include "base/error.h"
#include "bench/rays.h"
#include "bvh/bvh.h"
#include "gpu/context.h"
#include "scene/scene.h"

struct bench_scene_tree {
    struct cv_scene *sc;
    struct bench_tris m;   /* the static triangles the tree covers */
    struct cv_gpu *gpu;
    GLuint vb, tb;         /* vertices, triangles (bound at their slots) */
    struct cv_bvh *bvh;    /* bound */
};

/* Loads path, opens the first GPU and builds the tree with params; on
 * failure everything made is released and err says why. */
bool bench_scene_tree_open(const char *path, const struct cv_bvh_params *params,
                           struct bench_scene_tree *st, struct cv_error *err);

/* Releases the tree, the buffers and the GL context, keeping the scene
 * (rt_probe ends GL before Vulkan loads and still reads the scene). */
void bench_scene_tree_close_gpu(struct bench_scene_tree *st);

/* Everything, the scene included. */
void bench_scene_tree_close(struct bench_scene_tree *st);

#endif
