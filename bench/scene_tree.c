/* scene_tree.c: the traversal benchmarks' shared set-up (scene_tree.h). */
#include "config.h"

#include "bench/scene_tree.h"

#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"

bool bench_scene_tree_open(const char *path, const struct cv_bvh_params *params,
                           struct bench_scene_tree *st, struct cv_error *err)
{
    *st = (struct bench_scene_tree){0};
    if (!cv_scene_load(path, &(struct cv_scene_load_params){0}, &st->sc, err))
        return false;
    const struct cv_scene *sc = st->sc;
    st->m = (struct bench_tris){.v = sc->vertices, .t = sc->triangles,
                                .n = cv_scene_static_triangles(sc)};
    bool ok = true;
    if (st->m.n < 2)
        ok = cv_fail(err, "%s has fewer than 2 static triangles", path);
    ok = ok && cv_gpu_create(&(struct cv_gpu_params){.gpu_index = -1}, &st->gpu, err) &&
         (st->vb = cv_buffer_create((size_t)sc->n_vertices * sizeof(CvVertex), sc->vertices,
                                    "vertices", err)) &&
         (st->tb = cv_buffer_create((size_t)sc->n_triangles * sizeof(CvTriangle),
                                    sc->triangles, "triangles", err)) &&
         cv_bvh_build(st->gpu, st->vb, st->tb, st->m.n, params, &st->bvh, err);
    if (!ok) {
        bench_scene_tree_close(st);
        return false;
    }
    cv_buffer_bind(st->vb, CV_BIND_VERTICES);
    cv_buffer_bind(st->tb, CV_BIND_TRIANGLES);
    cv_bvh_bind(st->bvh);
    return true;
}

void bench_scene_tree_close_gpu(struct bench_scene_tree *st)
{
    cv_bvh_destroy(&st->bvh);
    cv_buffer_destroy(&st->vb);
    cv_buffer_destroy(&st->tb);
    cv_gpu_destroy(&st->gpu);
}

void bench_scene_tree_close(struct bench_scene_tree *st)
{
    bench_scene_tree_close_gpu(st);
    cv_scene_destroy(&st->sc);
}
