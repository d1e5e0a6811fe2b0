#!/usr/bin/env python3
"""make_measured.py: writes measured_ggx.bsdf, a small RGL tensor file (the
format of the EPFL RGL material database, read by pbrt-v4's `measured`
material) tabulating an analytic BRDF, for Cavalry's tests: no RGL files
are available offline. Run it from this folder; the output is committed.

The BRDF is an isotropic GGX conductor (alpha ALPHA, height-correlated
Smith masking) whose Fresnel term is Schlick's with a normal-incidence
reflectance R0(lambda) that rises from blue to red, so the colour varies
across the spectrum. It is laid out as Dupuy & Jakob's adaptive
parameterisation (and pbrt-v4's MeasuredBxDF) reads it:
  ndf[y][x]       D(wm) on the (u_theta, u_phi) square, u_theta = sqrt(theta / (pi/2)),
                  u_phi = phi / (2 pi) + 1/2
  sigma[y][x]     projected area of the microsurface towards w, (cos + sqrt(cos^2 + a^2 sin^2)) / 2
  vndf[phi_i][theta_i][y][x]  the visible normals of wo, as a density on that square
                  (D_wo(wm) times 2 pi^2 u_theta sin theta_m)
  spectra[phi_i][theta_i][lambda][y][x]  on the square of the vndf warp's
                  uniform points: the microfacet normal there is the warp's
                  image, and the value is F (1 + L(wo)) / (1 + L(wo) + L(wi)),
                  which makes f = spectra D / (4 sigma cos_i) the GGX BRDF
  luminance[..][y][x]  the spectra's luminance, for the second warp
Isotropic (one phi_i), so phi of wm is relative to phi of wo."""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
ALPHA = 0.3
N_THETA_I = 6          # theta_i nodes, uniform in u_theta over [0, 1]
N_VNDF = 16            # vndf, ndf and sigma grids, N x N
N_SPEC = 12            # luminance and spectra grids
WAVELENGTHS = [360.0, 420.0, 480.0, 540.0, 600.0, 660.0, 720.0, 830.0]


def r0(lam):
    return 0.15 + 0.75 / (1.0 + math.exp(-(lam - 540.0) / 30.0))


def u2theta(u):
    return u * u * math.pi / 2


def u2phi(u):
    return (2 * u - 1) * math.pi


def direction(theta, phi):
    s = math.sin(theta)
    return (s * math.cos(phi), s * math.sin(phi), math.cos(theta))


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def ggx_d(wm):
    c2 = wm[2] * wm[2]
    if c2 <= 0:
        return 0.0
    t2 = (1 - c2) / c2
    e = 1 + t2 / (ALPHA * ALPHA)
    return 1.0 / (math.pi * ALPHA * ALPHA * c2 * c2 * e * e)


def smith_lambda(w):
    c2 = w[2] * w[2]
    if c2 <= 0:
        return float("inf")
    t2 = (1 - c2) / c2
    return (-1 + math.sqrt(1 + ALPHA * ALPHA * t2)) / 2


def sigma(w):
    c = w[2]
    return (c + math.sqrt(c * c + ALPHA * ALPHA * (1 - c * c))) / 2


def grid(n):
    return [i / (n - 1) for i in range(n)]


def vndf_slice(wo):
    """The visible-normal density of wo on the (u_theta, u_phi) square, [y][x]."""
    out = []
    for uy in grid(N_VNDF):
        row = []
        for ux in grid(N_VNDF):
            th = u2theta(ux)
            wm = direction(th, u2phi(uy))  # phi relative to wo's (0 here)
            d = max(0.0, dot(wo, wm)) * ggx_d(wm) / sigma(wo)
            row.append(d * 2 * math.pi ** 2 * ux * math.sin(th))
        out.append(row)
    return out


class Warp:
    """A piecewise-bilinear density on [0,1]^2 and its sampling, as
    pbrt-v4's PiecewiseLinear2D (conditional CDFs along x per row, marginal
    along y)."""

    def __init__(self, data):
        self.ny, self.nx = len(data), len(data[0])
        cond = []
        for row in data:
            c, s = [0.0], 0.0
            for x in range(self.nx - 1):
                s += 0.5 * (row[x] + row[x + 1])
                c.append(s)
            cond.append(c)
        marg, s = [0.0], 0.0
        for y in range(self.ny - 1):
            s += 0.5 * (cond[y][-1] + cond[y + 1][-1])
            marg.append(s)
        self.data = [[v / s for v in row] for row in data]
        self.cond = [[v / s for v in row] for row in cond]
        self.marg = [v / s for v in marg]

    @staticmethod
    def interval(values, x):
        i = 0
        while i + 2 < len(values) and values[i + 1] < x:
            i += 1
        return i

    @staticmethod
    def solve(a, c0, c1):
        if abs(c0 - c1) < 1e-4 * (c0 + c1):
            return 2 * a / (c0 + c1)
        return (c0 - math.sqrt(max(c0 * c0 - 2 * a * (c0 - c1), 0.0))) / (c0 - c1)

    def sample(self, ux, uy):
        eps = 2.0 ** -24
        ux, uy = min(max(ux, eps), 1 - eps), min(max(uy, eps), 1 - eps)
        row = self.interval(self.marg, uy)
        uy -= self.marg[row]
        r0_, r1_ = self.cond[row][-1], self.cond[row + 1][-1]
        ty = self.solve(uy, r0_, r1_)
        ux *= (1 - ty) * r0_ + ty * r1_
        mixed = [(1 - ty) * a + ty * b for a, b in zip(self.cond[row], self.cond[row + 1])]
        col = self.interval(mixed, ux)
        ux -= mixed[col]
        c0 = (1 - ty) * self.data[row][col] + ty * self.data[row + 1][col]
        c1 = (1 - ty) * self.data[row][col + 1] + ty * self.data[row + 1][col + 1]
        tx = self.solve(ux, c0, c1)
        return (col + tx) / (self.nx - 1), (row + ty) / (self.ny - 1)


def luminance_weights():
    # CIE 1931 y-bar at the nodes (the multi-lobe Gaussian fit of Wyman et al.)
    def ybar(l):
        def g(mu, s1, s2):
            t = (l - mu) / (s1 if l < mu else s2)
            return math.exp(-0.5 * t * t)
        return 0.821 * g(568.8, 46.9, 40.5) + 0.286 * g(530.9, 16.3, 31.1)
    w = [ybar(l) for l in WAVELENGTHS]
    s = sum(w)
    return [v / s for v in w]


def tables():
    theta_i = [u2theta(u) for u in grid(N_THETA_I)]
    ndf = [[ggx_d(direction(u2theta(ux), u2phi(uy))) for ux in grid(N_VNDF)] for uy in grid(N_VNDF)]
    sig = [[sigma(direction(u2theta(ux), u2phi(uy))) for ux in grid(N_VNDF)] for uy in grid(N_VNDF)]
    lw = luminance_weights()
    vndf, spectra, lum = [], [], []
    for th_o in theta_i:
        wo = direction(th_o, 0.0)
        v = vndf_slice(wo)
        vndf.append(v)
        warp = Warp(v)
        lo = smith_lambda(wo) if wo[2] > 0 else float("inf")
        spec = [[[0.0] * N_SPEC for _ in range(N_SPEC)] for _ in WAVELENGTHS]
        lslice = [[0.0] * N_SPEC for _ in range(N_SPEC)]
        for j, uy in enumerate(grid(N_SPEC)):
            for i, ux in enumerate(grid(N_SPEC)):
                mx, my = warp.sample(ux, uy)
                wm = direction(u2theta(mx), u2phi(my))
                c = dot(wo, wm)
                wi = tuple(2 * c * m - o for m, o in zip(wm, wo))
                if wi[2] <= 0 or c <= 0:
                    continue
                li = smith_lambda(wi)
                g = 1.0 / (1 + li) if math.isinf(lo) else (1 + lo) / (1 + lo + li)
                vals = []
                for k, lam in enumerate(WAVELENGTHS):
                    f0 = r0(lam)
                    vals.append((f0 + (1 - f0) * (1 - c) ** 5) * g)
                    spec[k][j][i] = vals[-1]
                lslice[j][i] = sum(a * b for a, b in zip(vals, lw))
        spectra.append(spec)
        lum.append(lslice)
    return theta_i, ndf, sig, vndf, spectra, lum


def flat(x):
    if isinstance(x, list):
        for v in x:
            yield from flat(v)
    else:
        yield x


def write_tensor(path, fields):
    """fields: (name, dtype code, 'f' or 'B', shape, values)."""
    head = b"tensor_file\0" + bytes([1, 0]) + struct.pack("<I", len(fields))
    table_len = sum(2 + len(n) + 2 + 1 + 8 + 8 * len(shape) for n, _, _, shape, _ in fields)
    offset = len(head) + table_len
    table, blobs = b"", b""
    for name, code, fmt, shape, values in fields:
        offset = (offset + 7) & ~7
        blob = struct.pack("<%d%s" % (len(values), fmt), *values)
        pad = offset - (len(head) + table_len + len(blobs))
        blobs += b"\0" * pad + blob
        table += struct.pack("<H", len(name)) + name.encode() + struct.pack("<HBQ", len(shape), code, offset)
        table += b"".join(struct.pack("<Q", s) for s in shape)
        offset += len(blob)
    with open(path, "wb") as out:
        out.write(head + table + blobs)


def main():
    theta_i, ndf, sig, vndf, spectra, lum = tables()
    F32, U8 = 10, 1
    desc = ("Cavalry test BRDF: isotropic GGX conductor, alpha %g, Schlick Fresnel with "
            "R0 rising from blue to red (tests/data/trace/oracle/make_measured.py)" % ALPHA).encode()
    nl = len(WAVELENGTHS)
    fields = [
        ("description", U8, "B", [len(desc)], list(desc)),
        ("jacobian", U8, "B", [1], [1]),
        ("isotropic", U8, "B", [1], [1]),
        ("theta_i", F32, "f", [N_THETA_I], theta_i),
        ("phi_i", F32, "f", [1], [0.0]),
        ("wavelengths", F32, "f", [nl], WAVELENGTHS),
        ("ndf", F32, "f", [N_VNDF, N_VNDF], list(flat(ndf))),
        ("sigma", F32, "f", [N_VNDF, N_VNDF], list(flat(sig))),
        ("vndf", F32, "f", [1, N_THETA_I, N_VNDF, N_VNDF], list(flat(vndf))),
        ("luminance", F32, "f", [1, N_THETA_I, N_SPEC, N_SPEC], list(flat(lum))),
        ("spectra", F32, "f", [1, N_THETA_I, nl, N_SPEC, N_SPEC], list(flat(spectra))),
    ]
    write_tensor(os.path.join(HERE, "measured_ggx.bsdf"), fields)


if __name__ == "__main__":
    main()
