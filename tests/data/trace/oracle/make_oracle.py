#!/usr/bin/env python3
# make_oracle.py: writes the oracle scenes of tests/trace/oracle_test.c (run
# once; the .pbrt, .png and .pfm files are committed, as are the pbrt-v4
# references rendered from them, see README). Each scene isolates one
# feature: a material on a sphere over a grey floor, or one kind of light.
# Everything is a triangle mesh with explicit normals, so that pbrt-v4 and
# Cavalry intersect the same geometry.
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
RES = 32


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


def fmt(xs):
    return " ".join("%.6g" % x for x in xs)


def mesh(idx, p, n=None, uv=None):
    s = 'Shape "trianglemesh"\n  "integer indices" [ %s ]\n  "point3 P" [ %s ]' % (
        " ".join(str(i) for i in idx), fmt(p))
    if n:
        s += '\n  "normal N" [ %s ]' % fmt(n)
    if uv:
        s += '\n  "point2 uv" [ %s ]' % fmt(uv)
    return s + "\n"


def sphere_include():
    v, f = icosphere(3)
    idx = [i for tri in f for i in tri]
    p = [c for q in v for c in q]
    return ("# sphere.pbrt: unit icosphere (level 3, 1280 triangles) with its analytic\n"
            "# normals; made by make_oracle.py.\n" + mesh(idx, p, p))


def quad_y(h, y, down=False, uv_scale=1.0):
    """Square of half-size h in the plane y, normal +y (or -y when down)."""
    p = [-h, y, -h, h, y, -h, h, y, h, -h, y, h]
    uv = [0, 0, uv_scale, 0, uv_scale, uv_scale, 0, uv_scale]
    # pbrt-v4's triangle normal is cross(p0 - p2, p1 - p2): (0 1 2) faces -y here
    idx = [0, 1, 2, 0, 2, 3] if down else [0, 2, 1, 0, 3, 2]
    ny = -1 if down else 1
    return mesh(idx, p, [0, ny, 0] * 4, uv)


HEADER = """# %s: %s
# Made by make_oracle.py; reference: %s.exr (pbrt-v4, see README).
LookAt 0 2.6 -5.6  0 0.8 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Sampler "zsobol" "integer pixelsamples" [ 64 ]
Integrator "path" "integer maxdepth" [ %d ]
Film "rgb" "integer xresolution" [ %d ] "integer yresolution" [ %d ]
  "string sensor" "cie1931" "string filename" "%s.exr"
PixelFilter "box"
WorldBegin
"""

FLOOR = ('AttributeBegin\n  Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n  '
         + quad_y(5, 0).replace("\n", "\n  ").rstrip() + "\nAttributeEnd\n")

ENV_CONST = 'LightSource "infinite" "rgb L" [ 0.5 0.5 0.5 ]\n'
AREA_LAMP = ('AttributeBegin\n  AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]\n'
             '  Material "diffuse" "rgb reflectance" [ 0 0 0 ]\n  '
             + quad_y(0.75, 4, down=True).replace("\n", "\n  ").rstrip() + "\nAttributeEnd\n")
POINT = 'LightSource "point" "point3 from" [ 1.5 3 -1 ] "rgb I" [ 6 6 6 ]\n'
DISTANT = 'LightSource "distant" "point3 from" [ 1 2 -1.5 ] "point3 to" [ 0 0 0 ] "rgb L" [ 2 2 2 ]\n'


def sphere(material, at=(0, 1, 0)):
    return ("AttributeBegin\n  %s\n  Translate %g %g %g\n  Include \"sphere.pbrt\"\nAttributeEnd\n"
            % (material, at[0], at[1], at[2]))


def scene(name, what, body, maxdepth=5):
    with open(os.path.join(HERE, name + ".pbrt"), "w") as out:
        out.write(HEADER % (name + ".pbrt", what, name, maxdepth, RES, RES, name) + body)


# Materials: each on the sphere, lit by a constant environment (declared first:
# issue 24 bug 1 is a test of its own) and a square lamp above.
LIT = ENV_CONST + AREA_LAMP + FLOOR
MATERIALS = [
    ("mat_diffuse", "white diffuse", 'Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]'),
    ("mat_conductor_smooth", "smooth conductor, grey reflectance",
     'Material "conductor" "rgb reflectance" [ 0.8 0.8 0.8 ]'),
    ("mat_conductor_rough", "rough conductor (roughness 0.3), grey reflectance",
     'Material "conductor" "rgb reflectance" [ 0.8 0.8 0.8 ] "float roughness" [ 0.3 ]'),
    ("mat_conductor_cu", "rough copper (pbrt-v4's default spectral eta and k, roughness 0.2)",
     'Material "conductor" "float roughness" [ 0.2 ]'),
    ("mat_dielectric", "smooth glass, eta 1.5", 'Material "dielectric" "float eta" [ 1.5 ]'),
    ("mat_dielectric_rough", "rough glass, eta 1.5, roughness 0.3",
     'Material "dielectric" "float eta" [ 1.5 ] "float roughness" [ 0.3 ]'),
    ("mat_thindielectric", "thin dielectric, eta 1.5", 'Material "thindielectric" "float eta" [ 1.5 ]'),
    ("mat_coateddiffuse", "coated diffuse, smooth coat, white base",
     'Material "coateddiffuse" "rgb reflectance" [ 0.8 0.8 0.8 ] "float roughness" [ 0 ]'),
    ("mat_coateddiffuse_rough", "coated diffuse, coat roughness 0.3, thickness 0.1",
     'Material "coateddiffuse" "rgb reflectance" [ 0.8 0.8 0.8 ] "float roughness" [ 0.3 ]'
     ' "float thickness" [ 0.1 ]'),
    ("mat_coatedconductor", "coated conductor, smooth coat over a grey base of roughness 0.3",
     'Material "coatedconductor" "rgb reflectance" [ 0.8 0.8 0.8 ]'
     ' "float interface.roughness" [ 0 ] "float conductor.roughness" [ 0.3 ]'),
    ("mat_diffusetransmission", "diffuse transmission, reflectance 0.3, transmittance 0.6",
     'Material "diffusetransmission" "rgb reflectance" [ 0.3 0.3 0.3 ]'
     ' "rgb transmittance" [ 0.6 0.6 0.6 ]'),
]

GREY_SPHERE = sphere('Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]')


def spot():
    return ('LightSource "spot" "point3 from" [ 0 4 -1.5 ] "point3 to" [ 0 0 0.5 ] "rgb I" [ 12 12 12 ]\n'
            '  "float coneangle" [ 30 ] "float conedeltaangle" [ 10 ]\n')


def env_map():
    """Equal-area octahedral map (square) of a dim sky with one bright patch."""
    n = 32
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            u, v = (x + 0.5) / n, (y + 0.5) / n
            r, g, b = 0.3 + 0.4 * u, 0.4, 0.3 + 0.4 * v
            if abs(u - 0.3) < 0.07 and abs(v - 0.4) < 0.07:
                r, g, b = 20.0, 20.0, 20.0
            row.append((r, g, b))
        rows.append(row)
    # PFM rows run bottom to top
    with open(os.path.join(HERE, "envmap.pfm"), "wb") as out:
        out.write(b"PF\n%d %d\n-1.0\n" % (n, n))
        for row in reversed(rows):
            for px in row:
                out.write(struct.pack("<3f", *px))


def texture_png():
    """16x16 sRGB checker of greys with one coloured block, 8-bit PNG."""
    n = 16
    raw = b""
    for y in range(n):
        raw += b"\0"
        for x in range(n):
            if x < 8 and y < 8:
                px = (200, 60, 40) if (x // 2 + y // 2) % 2 else (230, 230, 230)
            else:
                px = (230, 230, 230) if (x // 4 + y // 4) % 2 else (40, 40, 40)
            raw += bytes(px)

    def chunk(kind, data):
        c = kind + data
        return struct.pack(">I", len(data)) + c + struct.pack(">I", zlib.crc32(c) & 0xffffffff)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(os.path.join(HERE, "checker.png"), "wb") as out:
        out.write(png)


def deep_bvh():
    """A spiral of triangles shrinking geometrically towards the sphere's top:
    sizes over six orders of magnitude make the tree deep."""
    idx, p = [], []
    k = 1200
    for i in range(k):
        s = 0.4 * 0.9912 ** i
        a = i * 0.7
        r = 1.6 * 0.997 ** i
        cx, cz, cy = r * math.cos(a), r * math.sin(a), 0.02 + 1.5 * (1 - 0.997 ** i)
        base = len(p) // 3
        p += [cx - s, cy, cz - s, cx + s, cy, cz - s, cx, cy, cz + s]
        idx += [base, base + 2, base + 1]
    return mesh(idx, p)


# Curves (issue 27): thick strands (covering most of the image) where the sphere
# stands elsewhere, lit from
# above (the lamp) and from the +x side (the distant light), which tells the
# two sides of a cylinder's bent normal apart.
CURVE_LIGHTS = ENV_CONST.replace("0.5 0.5 0.5", "0.3 0.3 0.3") + AREA_LAMP + DISTANT + FLOOR


def strand(x, kind, basis, degree, width, extra=""):
    """A wavy strand rising from the floor at x, as a curve of the given kind."""
    n = {("bspline", 3): 7, ("bezier", 3): 7, ("bezier", 2): 5}[(basis, degree)]
    p = []
    for i in range(n):
        t = i / (n - 1)
        p += [x + 0.35 * math.sin(5 * t), 0.15 + 2.0 * t, 0.3 * math.cos(4 * t)]
    return ('Shape "curve" "string type" "%s" "string basis" "%s" "integer degree" %d\n'
            '  "point3 P" [ %s ]\n  %s%s\n' % (kind, basis, degree, fmt(p), width, extra))


def curve_scenes():
    diffuse = 'Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]'
    scene("curve_diffuse", "diffuse curves: cylinder (b-spline), flat (Bezier, tapering), ribbon "
          "(quadratic Bezier, turning normals)",
          CURVE_LIGHTS + "AttributeBegin\n  " + diffuse + "\n"
          + strand(-1.15, "cylinder", "bspline", 3, '"float width" [ 0.8 ]')
          + strand(0.0, "flat", "bezier", 3, '"float width0" [ 0.9 ] "float width1" [ 0.4 ]')
          + strand(1.15, "ribbon", "bezier", 2, '"float width" [ 0.8 ]',
                   ' "normal N" [ 0.3 0 -1  -0.6 0.2 -1  0.2 0 -1 ]')
          + "AttributeEnd\n")
    scene("curve_hair", "hair on thick curves: cylinder b-splines of eumelanin 0.3 and of reflectance "
          "(0.8 0.5 0.3), a flat Bezier of sigma_a (0.2 0.4 0.8), beta_m 0.25, beta_n 0.4",
          CURVE_LIGHTS
          + 'AttributeBegin\n  Material "hair" "float eumelanin" [ 0.3 ] "float beta_m" [ 0.25 ]'
          ' "float beta_n" [ 0.4 ]\n'
          + strand(-1.15, "cylinder", "bspline", 3, '"float width" [ 0.8 ]') + "AttributeEnd\n"
          + 'AttributeBegin\n  Material "hair" "rgb reflectance" [ 0.8 0.5 0.3 ] "float beta_m" [ 0.25 ]'
          ' "float beta_n" [ 0.4 ]\n'
          + strand(0.0, "cylinder", "bspline", 3, '"float width" [ 0.8 ]') + "AttributeEnd\n"
          + 'AttributeBegin\n  Material "hair" "rgb sigma_a" [ 0.2 0.4 0.8 ] "float beta_m" [ 0.25 ]'
          ' "float beta_n" [ 0.4 ]\n'
          + strand(1.15, "flat", "bezier", 3, '"float width" [ 0.8 ]') + "AttributeEnd\n")


def main():
    with open(os.path.join(HERE, "sphere.pbrt"), "w") as out:
        out.write(sphere_include())
    env_map()
    texture_png()
    for name, what, mat in MATERIALS:
        scene(name, what, LIT + sphere(mat), maxdepth=8)
    scene("light_point", "point light", POINT + FLOOR + GREY_SPHERE)
    scene("light_spot", "spot light, cone 30 degrees, falloff 10", spot() + FLOOR + GREY_SPHERE)
    scene("light_distant", "distant light", DISTANT + FLOOR + GREY_SPHERE)
    scene("light_area", "one-sided square area light", AREA_LAMP + FLOOR + GREY_SPHERE)
    scene("light_env_const", "constant environment", ENV_CONST + FLOOR + GREY_SPHERE)
    scene("light_env_map", "equal-area environment map with a bright patch",
          'AttributeBegin\n  Rotate -90 1 0 0\n  LightSource "infinite" "string filename" "envmap.pfm"\n'
          'AttributeEnd\n' + FLOOR + GREY_SPHERE)
    scene("texture_image", "sRGB PNG image texture on the floor",
          ENV_CONST.replace("0.5 0.5 0.5", "0.2 0.2 0.2") + AREA_LAMP
          + 'Texture "checker" "spectrum" "imagemap" "string filename" "checker.png"\n'
          'AttributeBegin\n  Material "diffuse" "texture reflectance" "checker"\n  '
          + quad_y(5, 0).replace("\n", "\n  ").rstrip() + "\nAttributeEnd\n" + GREY_SPHERE)
    many = [ENV_CONST, DISTANT.replace("2 2 2", "1 1 1"), AREA_LAMP, POINT.replace("6 6 6", "3 3 3")]
    scene("lights_env_first", "environment, distant, area and point lights, the environment first",
          "".join(many) + FLOOR + GREY_SPHERE)
    scene("lights_env_last", "the same four lights, the environment last",
          "".join(many[1:] + many[:1]) + FLOOR + GREY_SPHERE)
    scene("huge_plane", "floor of half-size 100000 under a constant environment",
          ENV_CONST + 'AttributeBegin\n  Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n  '
          + quad_y(100000, 0).replace("\n", "\n  ").rstrip() + "\nAttributeEnd\n" + GREY_SPHERE)
    big_lamp = AREA_LAMP.replace("0.75", "1.5").replace("8 8 8", "5 5 5")
    scene("nee_area_env", "large lamp and constant environment over a rough conductor: every light "
          "can be found by BSDF sampling (tests/trace/nee_test.c)",
          ENV_CONST.replace("0.5 0.5 0.5", "0.25 0.25 0.25") + big_lamp + FLOOR
          + sphere(MATERIALS[2][2]), maxdepth=8)
    scene("deep_bvh", "1200 triangles shrinking geometrically (a deep BVH) over the floor",
          ENV_CONST + AREA_LAMP + FLOOR + 'AttributeBegin\n  Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]\n'
          + deep_bvh() + "AttributeEnd\n")
    # a white base under a smooth coat at pbrt-v4's default thickness, where
    # the walk's maxdepth shows (coated diffuse in closed form, issue 26)
    for md in (10, 100):
        scene("mat_coateddiffuse_white_md%d" % md, "coated diffuse, smooth coat, white base, maxdepth %d" % md,
              LIT + sphere('Material "coateddiffuse" "rgb reflectance" [ 1 1 1 ] "float roughness" [ 0 ]'
                           ' "integer maxdepth" [ %d ]' % md), maxdepth=8)
    curve_scenes()
    media_scenes()
    grid_scenes()
    measured_scenes()


# Camera and film (branch filmcam): scenes of emitters alone (maxdepth 1,
# black emitters), so that every pixel is the filter-, lens- or
# shutter-weighted coverage of bright geometry and nothing else.
CAMERA_HEADER = """# %s: %s
# Made by make_oracle.py; reference: %s.exr (pbrt-v4, see README).
%s
Sampler "zsobol" "integer pixelsamples" [ 64 ]
Integrator "path" "integer maxdepth" [ 1 ]
Film "rgb" "integer xresolution" [ %d ] "integer yresolution" [ %d ]
  "string sensor" "cie1931" "string filename" "%s.exr"
PixelFilter %s
WorldBegin
"""


def emitter(quads, L=4):
    """Black one-sided emitters facing -z (the cameras look along +z):
    quads are (x0, x1, y0, y1, z)."""
    idx, p, n = [], [], []
    for x0, x1, y0, y1, z in quads:
        b = len(p) // 3
        p += [x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z]
        n += [0, 0, -1] * 4
        idx += [b, b + 1, b + 2, b, b + 2, b + 3]
    return ('AttributeBegin\n  AreaLightSource "diffuse" "rgb L" [ %g %g %g ]\n'
            '  Material "diffuse" "rgb reflectance" [ 0 0 0 ]\n  ' % (L, L, L)
            + mesh(idx, p, n).replace("\n", "\n  ").rstrip() + "\nAttributeEnd\n")


def camera_scene(name, what, camera, pixel_filter, body):
    with open(os.path.join(HERE, name + ".pbrt"), "w") as out:
        out.write(CAMERA_HEADER % (name + ".pbrt", what, name, camera, RES, RES, name,
                                   pixel_filter) + body)


# Two lines one pixel wide (2/32 of the orthographic screen [-1, 1]): a
# vertical one over columns 11.2 to 12.2 and a horizontal one, nearer the
# camera, over rows 9.72 to 10.72 (oracle_test.c's line regions lie beside
# them): each pixel near a line is the filter's integral over the line.
LINES = emitter([(-0.3, -0.3 + 1 / 16, -2, 2, 0), (-2, 2, 0.33, 0.33 + 1 / 16, -0.1)])
ORTHO = "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"orthographic\""


def checker(n, size, z=0.0):
    """The bright squares of an n x n checker of side `size`, centred on the
    origin in the plane z."""
    h = n * size / 2
    return [(-h + i * size, -h + (i + 1) * size, -h + j * size, -h + (j + 1) * size, z)
            for j in range(n) for i in range(n) if (i + j) % 2 == 0]


def tilted_checker():
    """An 8 x 8 checker of side 0.5 about the origin, tilted 50 degrees about
    x (its top away from the camera)."""
    return ("AttributeBegin\n  Rotate -50 1 0 0\n" + emitter(checker(8, 0.5)).replace("\n", "\n  ").rstrip()
            + "\nAttributeEnd\n")


def camera_main():
    camera_scene("filter_mitchell", "thin bright lines through pbrt-v4's default Mitchell filter",
                 ORTHO, '"mitchell"', LINES)
    camera_scene("filter_sinc", "thin bright lines through a Lanczos (sinc) filter, radius 3, tau 2",
                 ORTHO, '"sinc" "float xradius" [ 3 ] "float yradius" [ 3 ] "float tau" [ 2 ]', LINES)
    camera_scene("camera_dof", "thin lens (radius 0.5) focused at 5 on a tilted checker",
                 'LookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective" "float fov" [ 30 ]\n'
                 '  "float lensradius" [ 0.5 ] "float focaldistance" [ 5 ]', '"box"', tilted_checker())
    camera_scene("camera_motion", "camera moving 0.3 right and rolling 8 degrees over the shutter,"
                 " before a checker",
                 'LookAt 0 0 -5  0 0 0  0 1 0\nActiveTransform EndTime\nRotate 8 0 0 1\n'
                 'Translate -0.3 0 0\nActiveTransform All\n'
                 'Camera "perspective" "float fov" [ 30 ]', '"box"', emitter(checker(8, 0.3)))


# Participating media (volpath; tests/trace/oracle_test.c renders scenes
# with media with Cavalry's volpath). Boundaries are "interface" surfaces
# (or glass) with a MediumInterface; inside is the side away from the
# normals, which point out of the volumes.

def box(lo, hi, inward=False):
    """Axis-aligned box as 6 quads (24 vertices) with outward normals
    (inward: the normals and winding turned into the box)."""
    faces = []
    for axis in range(3):
        for side in (0, 1):
            n = [0, 0, 0]
            n[axis] = 1 if side else -1
            u, v = (axis + 1) % 3, (axis + 2) % 3
            c = [lo, hi][side][axis]
            quad = []
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                pt = [0, 0, 0]
                pt[axis] = c
                pt[u] = [lo, hi][a][u]
                pt[v] = [lo, hi][b][v]
                quad.append(pt)
            # cross(p1 - p0, p2 - p0) points along +axis for this winding
            # (u, v, axis right-handed); flip it where the normal is -axis
            if (n[axis] < 0) != inward:
                quad = [quad[0], quad[3], quad[2], quad[1]]
            if inward:
                n = [-x for x in n]
            faces.append((quad, n))
    p, nn, idx = [], [], []
    for k, (quad, n) in enumerate(faces):
        for pt in quad:
            p += pt
            nn += n
        idx += [4 * k, 4 * k + 1, 4 * k + 2, 4 * k, 4 * k + 2, 4 * k + 3]
    return mesh(idx, p, nn)


def volpath_scene(name, what, body, maxdepth=20, before_camera=""):
    text = HEADER % (name + ".pbrt", what, name, maxdepth, RES, RES, name)
    text = text.replace('Integrator "path"', 'Integrator "volpath"')
    if before_camera:
        text = text.replace("LookAt", before_camera + "LookAt", 1)
    with open(os.path.join(HERE, name + ".pbrt"), "w") as out:
        out.write(text + body)


def indent(s):
    return "  " + s.replace("\n", "\n  ").rstrip() + "\n"


def media_scenes():
    # a grey scattering cube (albedo 0.9, forward g) on the floor under the lamp
    volpath_scene(
        "vol_cube", "homogeneous scattering cube (albedo 0.9, g 0.5) behind an interface, area lamp",
        AREA_LAMP + FLOOR
        + 'MakeNamedMedium "smoke" "string type" "homogeneous"\n'
          '  "rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 0.9 0.9 0.9 ] "float scale" [ 1.5 ]'
          ' "float g" [ 0.5 ]\n'
          'AttributeBegin\n  MediumInterface "smoke" ""\n  Material "interface"\n'
        + indent(box([-1, 0.01, -1], [1, 2, 1])) + "AttributeEnd\n")
    # a chromatic medium: sigma_s differs per channel
    volpath_scene(
        "vol_chromatic", "chromatic scattering sphere (sigma_s 0.6 1 1.6, sigma_a 0.1, g -0.3), "
        "environment and lamp",
        ENV_CONST + AREA_LAMP + FLOOR
        + 'MakeNamedMedium "dye" "string type" "homogeneous"\n'
          '  "rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 0.6 1 1.6 ] "float g" [ -0.3 ]\n'
        + sphere('MediumInterface "dye" ""\n  Material "interface"'))
    # the camera inside a foggy closed room: fog everywhere, no boundary
    room = ('AttributeBegin\n  Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n'
            + indent(box([-4, 0, -7], [4, 5, 4], inward=True)) + "AttributeEnd\n")
    volpath_scene(
        "vol_fog_room", "camera inside a closed room filled with fog (sigma_s 0.08, sigma_a 0.02), "
        "area lamp",
        AREA_LAMP + room + GREY_SPHERE,
        before_camera='MakeNamedMedium "fog" "string type" "homogeneous"\n'
                      '  "rgb sigma_a" [ 0.02 0.02 0.02 ] "rgb sigma_s" [ 0.08 0.08 0.08 ]\n'
                      'MediumInterface "" "fog"\n')
    # a smooth glass sphere filled with a scattering medium
    volpath_scene(
        "vol_glass", "smooth glass sphere (eta 1.5) filled with a scattering medium (sigma_s 2, "
        "sigma_a 0.2), environment and lamp",
        ENV_CONST + AREA_LAMP + FLOOR
        + 'MakeNamedMedium "milk" "string type" "homogeneous"\n'
          '  "rgb sigma_a" [ 0.2 0.2 0.2 ] "rgb sigma_s" [ 2 2 2 ]\n'
        + sphere('MediumInterface "milk" ""\n  Material "dielectric" "float eta" [ 1.5 ]'))


def floats(vals):
    return " ".join("%.4g" % v for v in vals)


def grid_scenes():
    # pbrt-v4's grid media: samples x fastest, then y, then z
    import math
    nx, ny, nz = 8, 6, 5
    dens = [(0.15 + 1.85 * x / (nx - 1)) * (1 + 0.4 * math.sin(1.3 * y + 0.7 * z))
            for z in range(nz) for y in range(ny) for x in range(nx)]
    # a density gradient, rotated and shifted by the CTM at MakeNamedMedium
    volpath_scene(
        "vol_grid_gradient", "uniformgrid 8x6x5 density gradient (sigma_s 1.5, sigma_a 0.2, "
        "scale 1.2, g 0.3) under a rotation, area lamp",
        AREA_LAMP + FLOOR
        + "AttributeBegin\n  Translate 0.1 0 0\n  Rotate 30 0 1 0\n"
          '  MakeNamedMedium "smoke" "string type" "uniformgrid"\n'
          '    "integer nx" [ %d ] "integer ny" [ %d ] "integer nz" [ %d ]\n'
          '    "point3 p0" [ -1 0.01 -1 ] "point3 p1" [ 1 2 1 ]\n'
          '    "rgb sigma_a" [ 0.2 0.2 0.2 ] "rgb sigma_s" [ 1.5 1.5 1.5 ] "float scale" [ 1.2 ]'
          ' "float g" [ 0.3 ]\n    "float density" [ %s ]\nAttributeEnd\n' % (nx, ny, nz, floats(dens))
        + 'AttributeBegin\n  MediumInterface "smoke" ""\n  Material "interface"\n'
        + indent(box([-1.6, 0.005, -1.6], [1.6, 2.2, 1.6])) + "AttributeEnd\n")
    # RGB grids: mildly chromatic scattering, absorption and emission
    n = 4
    sa, ss, le = [], [], []
    for z in range(n):
        for y in range(n):
            for x in range(n):
                k = 0.5 + 0.5 * math.cos(1.1 * x + 0.8 * y - 0.9 * z)
                sa += [0.1 + 0.2 * k, 0.1 + 0.15 * k, 0.1 + 0.1 * k]
                ss += [0.8 + 0.6 * k, 1.0 + 0.6 * k, 1.2 + 0.6 * k]
                hot = 1.0 if (x + y + z) % 3 == 0 else 0.0
                le += [0.02 * hot, 0.012 * hot, 0.006 * hot]
    volpath_scene(
        "vol_grid_rgb", "rgbgrid 4x4x4 (RGB sigma_a, sigma_s, Le; scale 1.3, Lescale 0.5, "
        "g -0.2), environment and lamp",
        ENV_CONST + AREA_LAMP + FLOOR
        + 'MakeNamedMedium "dye" "string type" "rgbgrid"\n'
          '  "integer nx" [ 4 ] "integer ny" [ 4 ] "integer nz" [ 4 ]\n'
          '  "point3 p0" [ -1 0.01 -1 ] "point3 p1" [ 1 2 1 ] "float scale" [ 1.3 ]'
          ' "float Lescale" [ 0.5 ] "float g" [ -0.2 ]\n'
          '  "rgb sigma_a" [ %s ]\n  "rgb sigma_s" [ %s ]\n  "rgb Le" [ %s ]\n'
          % (floats(sa), floats(ss), floats(le))
        + 'AttributeBegin\n  MediumInterface "dye" ""\n  Material "interface"\n'
        + indent(box([-1, 0.01, -1], [1, 2, 1])) + "AttributeEnd\n")
    # emission: a mostly absorbing density grid with a Lescale grid
    n = 5
    dens = [0.3 + 0.7 * ((x + 2 * y + z) % 4) / 3 for z in range(n) for y in range(n) for x in range(n)]
    les = [1.5 * (1 + math.cos(0.9 * x + 1.4 * y)) / 2 + 0.1 * z for z in range(n) for y in range(n) for x in range(n)]
    volpath_scene(
        "vol_grid_emission", "emissive uniformgrid 5x5x5 (rgb Le 2 1.2 0.6 times a Lescale grid; "
        "sigma_a 1, sigma_s 0.3), dim lamp",
        AREA_LAMP.replace("8 8 8", "1 1 1") + FLOOR
        + 'MakeNamedMedium "fire" "string type" "uniformgrid"\n'
          '  "integer nx" [ 5 ] "integer ny" [ 5 ] "integer nz" [ 5 ]\n'
          '  "point3 p0" [ -1 0.01 -1 ] "point3 p1" [ 1 2 1 ]\n'
          '  "rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 0.3 0.3 0.3 ] "rgb Le" [ 2 1.2 0.6 ]\n'
          '  "float density" [ %s ]\n  "float Lescale" [ %s ]\n' % (floats(dens), floats(les))
        + 'AttributeBegin\n  MediumInterface "fire" ""\n  Material "interface"\n'
        + indent(box([-1, 0.01, -1], [1, 2, 1])) + "AttributeEnd\n")
    # blackbody emission from a temperature grid (offset and scale), with
    # pbrt-v4's default Lescale: one sample, fading towards the bounds
    n = 4
    # (hot: Cavalry's fit of the CIE functions, spectrum.c, turns cooler
    # blackbodies' red up to 2 % darker than pbrt-v4's tables; README)
    temp = [3000 + 700 * ((x + y * z) % 4) + 200 * z for z in range(n) for y in range(n) for x in range(n)]
    volpath_scene(
        "vol_grid_blackbody", "uniformgrid 4x4x4 with a temperature grid (3000-5700, offset 200, "
        "scale 1.1; sigma_a 1, sigma_s 0.2), dim lamp",
        AREA_LAMP.replace("8 8 8", "1 1 1") + FLOOR
        + 'MakeNamedMedium "flame" "string type" "uniformgrid"\n'
          '  "integer nx" [ 4 ] "integer ny" [ 4 ] "integer nz" [ 4 ]\n'
          '  "point3 p0" [ -1 0.01 -1 ] "point3 p1" [ 1 2 1 ]\n'
          '  "rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 0.2 0.2 0.2 ]\n'
          '  "float temperatureoffset" [ 200 ] "float temperaturescale" [ 1.1 ]\n'
          '  "float density" [ %s ]\n  "float temperature" [ %s ]\n'
          % (floats([0.5 + 0.5 * ((x + y + z) % 2) for z in range(n) for y in range(n) for x in range(n)]),
             floats(temp))
        + 'AttributeBegin\n  MediumInterface "flame" ""\n  Material "interface"\n'
        + indent(box([-1, 0.01, -1], [1, 2, 1])) + "AttributeEnd\n")


# Object motion blur (issue 27): shapes under an animated transform
# (ActiveTransform EndTime), pbrt-v4's AnimatedTransform over the default
# shutter [0, 1] with a still camera. motion_main() writes it last (the
# earlier files come out unchanged).
def motion_main():
    white = 'Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]\n'
    # a box sliding 1 along +x
    slide = ("AttributeBegin\n  " + white + "  Translate -1.5 0 -0.2\n"
             "  ActiveTransform EndTime\n  Translate 1 0 0\n  ActiveTransform All\n"
             + indent(box([-0.4, 0, -0.4], [0.4, 0.8, 0.4])) + "AttributeEnd\n")
    # a plank turning 80 degrees about the vertical and growing to 1.5 times
    # its height: slerped rotation and lerped scale
    turn = ("AttributeBegin\n  " + white + "  Translate 1.2 0 0.4\n"
            "  ActiveTransform EndTime\n  Rotate 80 0 1 0\n  Scale 1 1.5 1\n  ActiveTransform All\n"
            + indent(box([-0.9, 0, -0.15], [0.9, 0.5, 0.15])) + "AttributeEnd\n")
    # a flattened sphere (smooth normals) rolling 60 degrees about z: its
    # shading normals go through the inverse transpose of the transform at
    # each time
    roll = ("AttributeBegin\n  " + white + "  Translate 0 1.1 1.6\n"
            "  ActiveTransform EndTime\n  Rotate 60 0 0 1\n  ActiveTransform All\n"
            "  Scale 0.9 0.45 0.9\n  Include \"sphere.pbrt\"\nAttributeEnd\n")
    scene("object_motion", "a box sliding, a plank turning and growing and a flattened sphere "
          "rolling over the shutter, area lamp", AREA_LAMP + FLOOR + slide + turn + roll, maxdepth=3)


def subsurface_scenes():
    # pbrt-v4's subsurface material on the sphere (radius 1) over the floor,
    # under the lamp and the environment: volpath, which is where pbrt-v4's
    # CPU integrators render a BSSRDF
    volpath_scene(
        "sss_grey", "subsurface sphere, grey sigma_a 0.05 sigma_s 4 (per unit), smooth boundary "
        "eta 1.33, environment and lamp",
        ENV_CONST + AREA_LAMP + FLOOR
        + sphere('Material "subsurface" "rgb sigma_a" [ 0.05 0.05 0.05 ]'
                 ' "rgb sigma_s" [ 4 4 4 ]'))
    volpath_scene(
        "sss_reflectance", "subsurface sphere from reflectance 0.7 and mfp 0.4, rough boundary "
        "(roughness 0.3, eta 1.5), g 0.3, environment and lamp",
        ENV_CONST + AREA_LAMP + FLOOR
        + sphere('Material "subsurface" "rgb reflectance" [ 0.7 0.7 0.7 ]'
                 ' "rgb mfp" [ 0.4 0.4 0.4 ] "float roughness" [ 0.3 ] "float eta" [ 1.5 ]'
                 ' "float g" [ 0.3 ]'))
    volpath_scene(
        "sss_skin", "subsurface sphere of pbrt-v4's measured \"Skin1\" (mm^-1, scale 10), "
        "environment and lamp",
        ENV_CONST + AREA_LAMP + FLOOR
        + sphere('Material "subsurface" "string name" "Skin1" "float scale" [ 10 ]'))
    # a textured reflectance, inverted to albedos per point (Cavalry: on
    # the GPU); a constant texture, which pbrt-v4 does not filter by the
    # ray's footprint (Cavalry filters no texture so: README)
    volpath_scene(
        "sss_texture", "subsurface sphere whose reflectance is a texture (constant 0.6), mfp 0.3, "
        "environment and lamp",
        ENV_CONST + AREA_LAMP + FLOOR
        + 'Texture "refl" "spectrum" "constant" "rgb value" [ 0.6 0.6 0.6 ]\n'
        + sphere('Material "subsurface" "texture reflectance" "refl" "rgb mfp" [ 0.3 0.3 0.3 ]'))
    # Skin1 channel by channel as grey media: pbrt-v4 renders sss_skin's
    # coloured coefficients spectrally, and Cavalry in RGB; channel c of
    # sss_skin_c's render is what an RGB renderer's channel c should give
    # (oracle_test.c compares sss_skin with the three so combined)
    skin = {"r": (0.032, 0.74), "g": (0.17, 0.88), "b": (0.48, 1.01)}
    for c, (sa, ss) in skin.items():
        volpath_scene(
            "sss_skin_" + c, "Skin1's %s channel alone as a grey subsurface sphere (sigma_a %g, "
            "sigma_s %g per mm, scale 10), environment and lamp" % (c, sa, ss),
            ENV_CONST + AREA_LAMP + FLOOR
            + sphere('Material "subsurface" "rgb sigma_a" [ %g %g %g ] "rgb sigma_s" [ %g %g %g ]'
                     ' "float scale" [ 10 ]' % (sa, sa, sa, ss, ss, ss)))


# Measured BRDFs (issue 27): the RGL tensor file of make_measured.py (an
# analytic GGX conductor whose colour varies across the spectrum) on the
# sphere, lit as the other materials.
def measured_scenes():
    scene("mat_measured", "measured BRDF (RGL tensor file measured_ggx.bsdf, make_measured.py)",
          LIT + sphere('Material "measured" "string filename" "measured_ggx.bsdf"'), maxdepth=8)


# Bidirectional transport (bdpt, tests/trace/bdpt_test.c): a smooth glass
# sphere's caustic on the floor under a small lamp, beside a rough
# conductor; the reference made by pbrt-v4's bdpt. The gaussian variant
# (no reference) checks light tracing's splats against our path.
def bdpt_main():
    small_lamp = AREA_LAMP.replace("0.75", "0.5").replace("8 8 8", "18 18 18")
    body = (small_lamp + FLOOR
            + sphere('Material "dielectric" "float eta" [ 1.5 ]', at=(-1.1, 1, 0))
            + sphere(MATERIALS[2][2], at=(1.1, 1, 0.3)))
    what = "glass sphere's caustic under a small lamp, beside a rough conductor"
    scene("bdpt_caustic", what, body, maxdepth=8)
    scene("bdpt_caustic_gaussian", what + ", gaussian filter", body, maxdepth=8)
    # the same spheres in sunlight (a distant light, which only light
    # subpaths bring through the glass: path renders no caustic)
    sun = 'LightSource "distant" "point3 from" [ -0.3 4 1.5 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3 3 3 ]\n'
    scene("bdpt_caustic_sun", "glass sphere's caustic in sunlight (a distant light), beside a "
          "rough conductor", sun + body[len(small_lamp):], maxdepth=8)
    for name, integrator, pixel_filter in (("bdpt_caustic", "bdpt", "box"),
                                           ("bdpt_caustic_gaussian", "bdpt", "gaussian"),
                                           ("bdpt_caustic_sun", "bdpt", "box")):
        path = os.path.join(HERE, name + ".pbrt")
        with open(path) as f:
            text = f.read()
        text = text.replace('Integrator "path"', 'Integrator "%s"' % integrator)
        text = text.replace('PixelFilter "box"', 'PixelFilter "%s"' % pixel_filter)
        with open(path, "w") as f:
            f.write(text)


# Medium presets and pbrt-v4's procedural cloud (issue 27). media_extra_main()
# writes them last (the earlier files come out unchanged).
def media_extra_main():
    # a homogeneous box of pbrt-v4's measured "Wholemilk" (mm^-1) times
    # scale: its only mildly chromatic sigma_s (README)
    volpath_scene(
        "vol_preset", "homogeneous box of the preset \"Wholemilk\" (scale 0.25, g 0.2) behind an "
        "interface, area lamp",
        AREA_LAMP + FLOOR
        + 'MakeNamedMedium "milk" "string type" "homogeneous" "string preset" "Wholemilk"\n'
          '  "float scale" [ 0.25 ] "float g" [ 0.2 ]\n'
          'AttributeBegin\n  MediumInterface "milk" ""\n  Material "interface"\n'
        + indent(box([-1, 0.01, -1], [1, 2, 1])) + "AttributeEnd\n")
    # pbrt-v4's cloud: noise-based density over bounds p0 p1 in medium
    # space, which the CTM at MakeNamedMedium scales and moves over the floor
    volpath_scene(
        "vol_cloud", "pbrt-v4's cloud medium (density 1.2, wispiness 1.5, frequency 3, sigma_s 3, "
        "sigma_a 0.3, g 0.4) in bounds 0 0.1 0 - 1 1 1 under a scale, area lamp",
        AREA_LAMP + FLOOR
        + "AttributeBegin\n  Translate -1.2 0.01 -1.2\n  Scale 2.4 2 2.4\n"
          '  MakeNamedMedium "cloud" "string type" "cloud"\n'
          '    "rgb sigma_a" [ 0.3 0.3 0.3 ] "rgb sigma_s" [ 3 3 3 ] "float g" [ 0.4 ]\n'
          '    "float density" [ 1.2 ] "float wispiness" [ 1.5 ] "float frequency" [ 3 ]\n'
          '    "point3 p0" [ 0 0.1 0 ] "point3 p1" [ 1 1 1 ]\nAttributeEnd\n'
        + 'AttributeBegin\n  MediumInterface "cloud" ""\n  Material "interface"\n'
        + indent(box([-1.3, 0.005, -1.3], [1.3, 2.1, 1.3])) + "AttributeEnd\n")


# pbrt-v4's "nanovdb" medium (issue 27): vol_nanovdb.nvdb (make_nanovdb.py)
# holds a 12x10x8-voxel density grid and a temperature grid poking out of
# its top; turned and moved by the CTM at MakeNamedMedium. The .pbrt names
# the ZIP-compressed file; the reference was rendered from
# vol_nanovdb_raw.nvdb (README). nanovdb_scenes() writes it last.
def nanovdb_scenes(nvdb="vol_nanovdb.nvdb"):
    volpath_scene(
        "vol_nanovdb", "nanovdb density and temperature grids (sigma_a 0.5, sigma_s 1.6, "
        "scale 1.1, g 0.4, Lescale 0.025, temperatureoffset 100, temperaturescale 1.2) under a "
        "rotation, area lamp",
        AREA_LAMP + FLOOR
        + "AttributeBegin\n  Translate 0.1 0 0.2\n  Rotate 25 0 1 0\n"
          '  MakeNamedMedium "cloud" "string type" "nanovdb" "string filename" "%s"\n'
          '    "rgb sigma_a" [ 0.5 0.5 0.5 ] "rgb sigma_s" [ 1.6 1.6 1.6 ] "float scale" [ 1.1 ]'
          ' "float g" [ 0.4 ]\n    "float Lescale" [ 0.025 ] "float temperatureoffset" [ 100 ]'
          ' "float temperaturescale" [ 1.2 ]\nAttributeEnd\n' % nvdb
        + 'AttributeBegin\n  MediumInterface "cloud" ""\n  Material "interface"\n'
        + indent(box([-1.8, 0.005, -1.8], [1.8, 2.4, 1.8])) + "AttributeEnd\n")


# pbrt-v4's own unbiased estimate of a rough coat: mat_coateddiffuse_rough
# rendered by BSDF sampling alone (simplepath, no light sampling), which
# uses the layered walk and not LayeredBxDF::f, whose exit weights through
# a rough coat make pbrt-v4's path (light sampling with MIS) brighter
# (oracle_test.c). Cavalry renders it with its path integrator.
def bsdf_only_main():
    name = "mat_coateddiffuse_rough_bsdf"
    for m in MATERIALS:
        if m[0] == "mat_coateddiffuse_rough":
            scene(name, m[1] + ", by BSDF sampling alone", LIT + sphere(m[2]), maxdepth=8)
    path = os.path.join(HERE, name + ".pbrt")
    with open(path) as f:
        text = f.read()
    text = text.replace('Integrator "path" "integer maxdepth" [ 8 ]',
                        'Integrator "simplepath" "integer maxdepth" [ 8 ] "bool samplelights" false')
    with open(path, "w") as f:
        f.write(text)


# bdpt's cameras (issue 27): bdpt_caustic's spheres under the lamp of the
# other scenes, seen by an orthographic camera, pinhole and thin lens
# (pbrt-v4's bdpt refuses any camera but the perspective one: their
# references are made by pbrt-v4's path, README), and by a camera that
# moves 0.4 sideways and rolls 6 degrees over the shutter while the glass
# sphere slides 0.4 along -x (the reference made by pbrt-v4's bdpt).
# bdpt_camera_main() writes them last (the earlier files come out
# unchanged).
def bdpt_camera_main():
    conductor = sphere(MATERIALS[2][2], at=(1.1, 1, 0.3))
    # under the lamp of the other scenes, larger than bdpt_caustic's: its
    # image in the glass, which only s = 0 finds, is then not too noisy for
    # the regions' means
    body = (AREA_LAMP + FLOOR + sphere('Material "dielectric" "float eta" [ 1.5 ]', at=(-1.1, 1, 0))
            + conductor)
    perspective = 'Camera "perspective" "float fov" [ 40 ]'
    ortho = 'Camera "orthographic" "float screenwindow" [ -2.5 2.5 -2.5 2.5 ]'
    lens = ortho + '\n  "float lensradius" [ 0.2 ] "float focaldistance" [ 5.9 ]'
    moving = ('ActiveTransform EndTime\nRotate 6 0 0 1\nTranslate -0.4 0 0\nActiveTransform All\n'
              + perspective)
    sliding = ('AttributeBegin\n  Material "dielectric" "float eta" [ 1.5 ]\n  Translate -1.1 1 0\n'
               '  ActiveTransform EndTime\n  Translate -0.4 0 0\n  ActiveTransform All\n'
               '  Include "sphere.pbrt"\nAttributeEnd\n')
    for name, what, camera, b in (
            ("bdpt_ortho", "bdpt_caustic's spheres under a lamp through an orthographic camera",
             ortho, body),
            ("bdpt_ortho_lens", "bdpt_caustic's spheres under a lamp through an orthographic "
             "thin lens (radius 0.2, focused at 5.9)", lens, body),
            ("bdpt_motion", "bdpt_caustic's spheres under a lamp, the camera moving 0.4 and "
             "rolling 6 degrees and the glass sphere sliding 0.4 over the shutter",
             moving, AREA_LAMP + FLOOR + sliding + conductor)):
        scene(name, what, b, maxdepth=8)
        path = os.path.join(HERE, name + ".pbrt")
        with open(path) as f:
            text = f.read()
        text = text.replace('Integrator "path"', 'Integrator "bdpt"').replace(perspective, camera)
        with open(path, "w") as f:
            f.write(text)
# Participating media in bdpt (issue 27, tests/trace/bdpt_test.c): the
# references made by pbrt-v4's bdpt. bdpt_media_main() writes them last
# (the earlier files come out unchanged).
def bdpt_media_main():
    def bdpt_scene(name, what, body, maxdepth=6, before_camera=""):
        volpath_scene(name, what, body, maxdepth=maxdepth, before_camera=before_camera)
        path = os.path.join(HERE, name + ".pbrt")
        with open(path) as f:
            text = f.read()
        with open(path, "w") as f:
            f.write(text.replace('Integrator "volpath"', 'Integrator "bdpt"'))

    def lamp(half, y, L, interface):
        return ('AttributeBegin\n  %s\n  AreaLightSource "diffuse" "rgb L" [ %g %g %g ]\n'
                '  Material "diffuse" "rgb reflectance" [ 0 0 0 ]\n  ' % (interface, L, L, L)
                + quad_y(half, y, down=True).replace("\n", "\n  ").rstrip() + "\nAttributeEnd\n")
    fog_box = ('AttributeBegin\n  MediumInterface "fog" ""\n  Material "interface"\n'
               + indent(box([-1.5, 0.01, -1.5], [1.5, 2.5, 1.5])) + "AttributeEnd\n")
    # (a) a small lamp inside a box of fog (the lamp's own MediumInterface
    # puts it in the fog on both sides), over a diffuse sphere in the fog
    bdpt_scene(
        "bdpt_vol_lamp", "small area lamp inside a box of homogeneous fog (sigma_s 0.6, sigma_a "
        "0.1, g 0.3) over a diffuse sphere in it",
        FLOOR + 'MakeNamedMedium "fog" "string type" "homogeneous"\n'
                '  "rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 0.6 0.6 0.6 ] "float g" [ 0.3 ]\n'
        + lamp(0.25, 2.3, 30, 'MediumInterface "fog" "fog"') + fog_box
        + sphere('MediumInterface "fog" "fog"\n  Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]'))
    # (b) a tiny volumetric caustic: a small bright lamp above a glass
    # sphere (vacuum inside) in a box of fog, as ../shared's
    # volumetric-caustic: the lamp's interface has the fog outside
    bdpt_scene(
        "bdpt_vol_caustic", "small bright lamp above a glass sphere (eta 1.5) in a box of fog "
        "(sigma_s 0.5, sigma_a 0): a volumetric caustic",
        FLOOR + 'MakeNamedMedium "fog" "string type" "homogeneous"\n'
                '  "rgb sigma_a" [ 0 0 0 ] "rgb sigma_s" [ 0.5 0.5 0.5 ]\n'
        + lamp(0.2, 2.4, 60, 'MediumInterface "" "fog"') + fog_box
        + sphere('MediumInterface "" "fog"\n  Material "dielectric" "float eta" [ 1.5 ]',
                 at=(0, 1.1, 0)))
    # (c) the camera and a point light inside a closed room of mildly
    # chromatic fog
    room = ('AttributeBegin\n  Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n'
            + indent(box([-3, 0, -6.5], [3, 4, 3], inward=True)) + "AttributeEnd\n")
    bdpt_scene(
        "bdpt_vol_chromatic", "camera and point light inside a closed room of chromatic fog "
        "(sigma_s 0.06 0.1 0.16, sigma_a 0.02, g -0.2), diffuse sphere",
        'LightSource "point" "point3 from" [ 1 3 -1 ] "rgb I" [ 10 10 10 ]\n' + room + GREY_SPHERE,
        before_camera='MakeNamedMedium "fog" "string type" "homogeneous"\n'
                      '  "rgb sigma_a" [ 0.02 0.02 0.02 ] "rgb sigma_s" [ 0.06 0.1 0.16 ]'
                      ' "float g" [ -0.2 ]\n'
                      'MediumInterface "" "fog"\n')


# Curves in object definitions and moving curves (issue 27): the strands of
# curve_diffuse in an ObjectBegin tuft instanced three times under
# different transforms; then a strand sliding and turning over the
# shutter beside a moving instance of a curve object. Uniform scales:
# other transforms are curve_scale's. The moving instance does not turn:
# turning instances are instance_turn's.
# curve_instance_main() writes them last (the earlier files come out
# unchanged).
def curve_instance_main():
    diffuse = 'Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]\n'
    tuft = ('ObjectBegin "tuft"\n  ' + diffuse + "  "
            + strand(-0.25, "cylinder", "bspline", 3, '"float width" [ 0.4 ]')
            + "  " + strand(0.25, "flat", "bezier", 3, '"float width0" [ 0.45 ] "float width1" [ 0.2 ]')
            + "  " + strand(0.0, "ribbon", "bezier", 2, '"float width" [ 0.35 ]',
                            ' "normal N" [ 0.3 0 -1  -0.6 0.2 -1  0.2 0 -1 ]')
            + "ObjectEnd\n")
    scene("curve_instance", "an object of three curves (cylinder, flat, ribbon) instanced three times: "
          "translated, turned and scaled, tilted",
          CURVE_LIGHTS + tuft
          + "AttributeBegin\n  Translate -1.25 0 0\n  ObjectInstance \"tuft\"\nAttributeEnd\n"
          + "AttributeBegin\n  Translate 0.1 0 0.3\n  Rotate 50 0 1 0\n  Scale 0.85 0.85 0.85\n"
            "  ObjectInstance \"tuft\"\nAttributeEnd\n"
          + "AttributeBegin\n  Translate 1.3 0 0\n  Rotate -25 0 0 1\n  ObjectInstance \"tuft\"\n"
            "AttributeEnd\n")
    mover = ("AttributeBegin\n  " + diffuse + "  Translate -1.4 0 0\n"
             "  ActiveTransform EndTime\n  Translate 0.9 0 0\n  Rotate 30 0 0 1\n  ActiveTransform All\n  "
             + strand(0.0, "cylinder", "bspline", 3, '"float width" [ 0.5 ]') + "AttributeEnd\n")
    turning = ("AttributeBegin\n  Translate 1.1 0 0\n"
               "  ActiveTransform EndTime\n  Translate 0 0 0.8\n  Scale 1.3 1.3 1\n  ActiveTransform All\n"
               "  ObjectInstance \"tuft\"\nAttributeEnd\n")
    scene("curve_motion", "a cylinder curve sliding and tilting over the shutter, and an instance of a "
          "curve object receding and growing",
          CURVE_LIGHTS + tuft + mover + turning)


# Moving instances that turn (issue 27): pbrt-v4 interpolates a moving
# instance's transform in render space, conjugated by the camera's position
# (its default "cameraworld"), so the instance's point at the camera, not
# its origin, moves along a line: a turning instance sweeps other arcs than
# a turning shape does. An object of a plank and a cylinder curve, turning
# about the vertical on the left and tilting about z on the right.
# instance_turn_main() writes it last (the earlier files come out unchanged).
def instance_turn_main():
    obj = ('ObjectBegin "plank"\n  Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]\n'
           + indent(box([-0.8, 0, -0.15], [0.8, 0.6, 0.15]))
           + "  " + strand(0.0, "cylinder", "bspline", 3, '"float width" [ 0.3 ]') + "ObjectEnd\n")
    turn = ("AttributeBegin\n  Translate -1.1 0 0.3\n"
            "  ActiveTransform EndTime\n  Rotate 50 0 1 0\n  ActiveTransform All\n"
            "  ObjectInstance \"plank\"\nAttributeEnd\n")
    tilt = ("AttributeBegin\n  Translate 1.1 0 0.3\n"
            "  ActiveTransform EndTime\n  Rotate -30 0 0 1\n  ActiveTransform All\n"
            "  ObjectInstance \"plank\"\nAttributeEnd\n")
    scene("instance_turn", "an object of a plank and a cylinder curve, instanced moving: turning 50 "
          "degrees about the vertical, tilting 30 degrees about z", CURVE_LIGHTS + obj + turn + tilt)


# Curves under transforms that are no similarity (issue 27): pbrt-v4 takes
# a curve's width, and a ribbon's normals, in object space and intersects
# there, so under a non-uniform scale or a shear a curve is as much wider
# or narrower as the transform stretches it across. A cylinder stretched
# across, a flat curve sheared, a ribbon squeezed in x and stretched in z
# (its normals through the inverse transpose), and an object of one
# cylinder strand instanced under a non-uniform scale, moving back.
# curve_scale_main() writes it last (the earlier files come out unchanged).
def curve_scale_main():
    diffuse = 'Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]\n'
    cyl = ("AttributeBegin\n  " + diffuse + "  Translate -1.2 0 0\n  Scale 2 0.6 1\n  "
           + strand(0.0, "cylinder", "bspline", 3, '"float width" [ 0.45 ]') + "AttributeEnd\n")
    flat = ("AttributeBegin\n  " + diffuse + "  Translate -0.1 0 0\n"
            "  ConcatTransform [ 1.5 0 0 0  0.35 1 0 0  0 0.3 1 0  0 0 0 1 ]\n  "
            + strand(0.0, "flat", "bezier", 3, '"float width0" [ 0.4 ] "float width1" [ 0.2 ]') + "AttributeEnd\n")
    ribbon = ("AttributeBegin\n  " + diffuse + "  Translate 1.2 0 0\n  Scale 0.5 1 2\n  "
              + strand(0.0, "ribbon", "bezier", 2, '"float width" [ 0.7 ]',
                       ' "normal N" [ 0.6 0 -1  -0.8 0.2 -1  0.4 0 -1 ]') + "AttributeEnd\n")
    wisp = ('ObjectBegin "wisp"\n  ' + diffuse + "  Scale 1 1 0.5\n  "
            + strand(0.0, "cylinder", "bezier", 3, '"float width" [ 0.4 ]') + "ObjectEnd\n")
    inst = ("AttributeBegin\n  Translate 0.5 0 1.6\n  Scale 1.7 0.9 1\n"
            "  ActiveTransform EndTime\n  Translate 0 0 0.3\n  ActiveTransform All\n"
            "  ObjectInstance \"wisp\"\nAttributeEnd\n")
    scene("curve_scale", "curves under non-uniform scales and a shear (cylinder, flat, ribbon) and a moving "
          "instance of a curve object under a non-uniform scale", CURVE_LIGHTS + wisp + cyl + flat + ribbon + inst)


# pbrt-v4's "spherical" camera (both mappings) and a cut-out emitter
# (DiffuseAreaLight's AlphaMasked), which landed without references.
# The spherical camera sees every direction: a floor, a grey sphere before
# it and a smaller white one behind and beside it, under a dim constant
# environment and a distant light (no small bright lamp: a few of its
# pixels would outweigh the rest of the image). It looks down with its up
# vector towards the grey sphere, so that the sky is not the middle of the
# equal-area image. The cut-out emitter is a
# one-sided lamp standing behind the floor's middle, facing the camera,
# under a dim environment: a 4x4 checker of alpha 1 and 0 (each point
# wholly kept or cut: the renderers' hashes play no part), and alpha 0.5
# (pbrt-v4 passes half of the rays by a hash of the ray and masks half of
# the lamp's points by a hash of the point, for its light samples and the
# rays that hit it). spherical_alpha_main() writes them last (the earlier
# files come out unchanged).
def spherical_alpha_main():
    perspective = 'LookAt 0 2.6 -5.6  0 0.8 0  0 1 0\nCamera "perspective" "float fov" [ 40 ]'
    white = ('AttributeBegin\n  Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]\n'
             '  Translate 1.4 0.5 -3.2\n  Scale 0.5 0.5 0.5\n  Include "sphere.pbrt"\nAttributeEnd\n')
    body = ENV_CONST.replace("0.5 0.5 0.5", "0.2 0.2 0.2") + DISTANT + FLOOR + GREY_SPHERE + white
    for name, mapping in (("camera_spherical_equalarea", "equalarea"),
                          ("camera_spherical_equirect", "equirectangular")):
        scene(name, "pbrt-v4's spherical camera, mapping \"%s\", beside a sphere over the floor"
              % mapping, body)
        path = os.path.join(HERE, name + ".pbrt")
        with open(path) as f:
            text = f.read()
        text = text.replace(perspective, 'LookAt 0 1.2 -2.4  0 0 -2.4  0 0 1\n'
                            'Camera "spherical" "string mapping" "%s"' % mapping)
        with open(path, "w") as f:
            f.write(text)
    x0, x1, y0, y1, z = -1.6, 1.6, 0.3, 2.3, 1.5
    lamp = mesh([0, 1, 2, 0, 2, 3], [x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z], [0, 0, -1] * 4,
                [0, 0, 1, 0, 1, 1, 0, 1])
    dim = ENV_CONST.replace("0.5 0.5 0.5", "0.2 0.2 0.2")
    checks = ('Texture "checks" "float" "checkerboard" "float uscale" [ 4 ] "float vscale" [ 4 ]\n'
              '  "float tex1" [ 1 ] "float tex2" [ 0 ]\n')
    for name, what, tex, alpha in (
            ("light_alpha_checker", "a lamp cut out by a 4x4 checker of alpha 1 and 0", checks,
             '"texture alpha" "checks"'),
            ("light_alpha_half", "a lamp of alpha 0.5", "", '"float alpha" [ 0.5 ]')):
        lit = ('AttributeBegin\n  AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]\n'
               '  Material "diffuse" "rgb reflectance" [ 0 0 0 ]\n  '
               + lamp.replace("\n", "\n  ").rstrip() + "\n    " + alpha + "\nAttributeEnd\n")
        scene(name, what + " standing behind the floor, facing the camera", dim + tex + FLOOR + lit)


# texture_image's scene with its floor a bilinear patch without uv, given
# as a PLY quad (pbrt-v4 makes a PLY quad a patch, v0 v1 v3 v2) and as a
# bilinearmesh: both take the patch's own (u, v), here those of
# texture_image's floor. ply_quad_main() writes them last (the earlier
# files come out unchanged).
def ply_quad_main():
    h = 5
    with open(os.path.join(HERE, "floor_quad.ply"), "w") as out:
        out.write("ply\nformat ascii 1.0\ncomment made by make_oracle.py: a quad without uv\n"
                  "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                  "%g 0 %g\n%g 0 %g\n%g 0 %g\n%g 0 %g\n4 0 1 2 3\n" % (-h, -h, h, -h, h, h, -h, h))
    patch = 'Shape "bilinearmesh" "point3 P" [ %s ]' % fmt([-h, 0, -h, h, 0, -h, -h, 0, h, h, 0, h])
    for name, what, shape in (
            ("texture_ply_quad", "texture_image's floor as a PLY quad without uv",
             'Shape "plymesh" "string filename" "floor_quad.ply"'),
            ("texture_bilinear_patch", "texture_image's floor as a bilinear patch without uv", patch)):
        scene(name, what, ENV_CONST.replace("0.5 0.5 0.5", "0.2 0.2 0.2") + AREA_LAMP
              + 'Texture "checker" "spectrum" "imagemap" "string filename" "checker.png"\n'
              'AttributeBegin\n  Material "diffuse" "texture reflectance" "checker"\n  '
              + shape + '\nAttributeEnd\n' + GREY_SPHERE)


if __name__ == "__main__":
    main()
    camera_main()
    motion_main()
    subsurface_scenes()
    bdpt_main()
    media_extra_main()
    nanovdb_scenes()
    bsdf_only_main()
    bdpt_camera_main()
    bdpt_media_main()
    curve_instance_main()
    instance_turn_main()
    curve_scale_main()
    spherical_alpha_main()
    ply_quad_main()
