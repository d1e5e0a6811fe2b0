#!/usr/bin/env python3
# make_scenes.py: writes the small test scenes of tests/trace (run once; the
# .pbrt files are committed). Spheres are icospheres written as triangle
# meshes with their analytic normals, so tests stay small.
import math


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache = {}

        def mid(a, b):
            k = (min(a, b), max(a, b))
            if k not in cache:
                p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                cache[k] = len(v) - 1
            return cache[k]
        nf = []
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return v, f


def mesh(level, radius, center=(0, 0, 0), flip=False):
    v, f = icosphere(level)
    if flip:
        f = [(a, c, b) for a, b, c in f]
    idx = " ".join("%d %d %d" % t for t in f)
    P = " ".join("%.7g %.7g %.7g" % tuple(center[i] + radius * p[i] for i in range(3)) for p in v)
    N = " ".join("%.7g %.7g %.7g" % ((-1 if flip else 1) * p[0], (-1 if flip else 1) * p[1],
                                     (-1 if flip else 1) * p[2]) for p in v)
    return ('Shape "trianglemesh" "integer indices" [ %s ]\n  "point3 P" [ %s ]\n'
            '  "normal N" [ %s ]\n' % (idx, P, N))


def write(name, text):
    with open(name, "w") as fh:
        fh.write(text)


LEVEL = 3
# pbrt's analytic test: inside a diffuse sphere (Kd 0.5) with a point light of
# intensity pi at its centre every point has radiance 1.
write("analytic.pbrt", """# analytic.pbrt: inside a diffuse sphere (reflectance 0.5, radius 1) lit by a
# point light of intensity pi at its centre, radiance is 1 everywhere
# (L = (Kd/pi) E + Kd L with E = pi). Made by make_scenes.py.
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 60 ]
Sampler "sobol" "integer pixelsamples" [ 64 ]
Integrator "path" "integer maxdepth" [ 100 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ] "string filename" "analytic.exr"
PixelFilter "box"
WorldBegin
LightSource "point" "rgb I" [ 3.14159265 3.14159265 3.14159265 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
""" + mesh(LEVEL, 1.0, flip=True))

# white furnace: a reflectance-1 diffuse sphere in a uniform environment of
# radiance 1 reads 1 everywhere (background included).
write("furnace.pbrt", """# furnace.pbrt: white furnace: a diffuse sphere of reflectance 1 inside a
# uniform environment of radiance 1 reads 1 everywhere. Made by make_scenes.py.
LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Sampler "sobol" "integer pixelsamples" [ 64 ]
Integrator "path" "integer maxdepth" [ 100 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ] "string filename" "furnace.exr"
PixelFilter "gaussian"
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
Material "diffuse" "rgb reflectance" [ 1 1 1 ]
""" + mesh(LEVEL, 1.0))

# a diffuse quad lit by a small area light: exercises area lights, MIS and
# the AOVs (depth and normal are known).
write("quad.pbrt", """# quad.pbrt: a grey floor quad under a square area light, seen from above.
# Made by make_scenes.py.
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Sampler "independent" "integer pixelsamples" [ 16 ]
Integrator "path" "integer maxdepth" [ 5 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 16 ] "string filename" "quad.exr"
PixelFilter "triangle"
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
  Translate 0 0 2
  Shape "trianglemesh" "integer indices" [ 0 2 1 0 3 2 ]
    "point3 P" [ -0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ]
  "point3 P" [ -10 -10 0  10 -10 0  10 10 0  -10 10 0 ]
""")
