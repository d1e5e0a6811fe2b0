#!/usr/bin/env python3
"""make_nanovdb.py: writes vol_nanovdb.nvdb, the NanoVDB file of the oracle
scene vol_nanovdb.pbrt (pbrt-v4's "nanovdb" medium): a "density" and a
"temperature" float grid (class FogVolume) made from procedural values,
in NanoVDB's file format 32.x (the layout of nanovdb/NanoVDB.h and
nanovdb/util/IO.h: a segment header, one metadata record per grid, then
each grid's buffer of grid, tree, root with its tiles, upper, lower and
leaf nodes, breadth first).

  make_nanovdb.py              vol_nanovdb.nvdb, ZIP-compressed (committed)
  make_nanovdb.py --codec none vol_nanovdb_raw.nvdb, uncompressed: what the
                               oracle's pbrt-v4 (built without zlib support
                               in NanoVDB) read to render the reference

Run from this folder. Both files hold the same grids byte for byte."""
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

MAGIC = 0x304244566F6E614E            # "NanoVDB0"
VERSION = (32 << 21) | (3 << 10) | 3   # 32.3.3, pbrt-v4's NanoVDB
GRID_TYPE_FLOAT = 1
GRID_CLASS_FOG_VOLUME = 2
FLAGS = 2 | 4 | 8 | 16 | 32            # bbox, min/max, average, std dev, breadth first
CODEC = {"none": 0, "zip": 1}

# node sizes and offsets of a float tree (PNanoVDB.h's table for type 1)
GRID_SIZE, TREE_SIZE, ROOT_SIZE, TILE_SIZE = 672, 64, 64, 32
UPPER_SIZE, UPPER_STATS, UPPER_TABLE = 270400, 8224, 8256
LOWER_SIZE, LOWER_STATS, LOWER_TABLE = 33856, 1056, 1088
LEAF_SIZE, LEAF_STATS, LEAF_TABLE = 2144, 80, 96


def stats(vals):
    n = len(vals)
    if n == 0:
        return (0.0, 0.0, 0.0, 0.0)
    avg = sum(vals) / n
    var = sum((v - avg) ** 2 for v in vals) / n
    return (min(vals), max(vals), avg, math.sqrt(var))


def bbox(coords):
    return ([min(c[a] for c in coords) for a in range(3)],
            [max(c[a] for c in coords) for a in range(3)])


def set_bit(mask, n):
    mask[n >> 5] |= 1 << (n & 31)


def grid_buffer(name, voxels, voxel_size, origin):
    """voxels: {(i, j, k): value}, all active, i, j, k >= 0 (one root tile
    per upper node); index to world: voxel_size * ijk + origin."""
    leaves, lowers, uppers = {}, {}, {}
    for (i, j, k) in voxels:
        leaves.setdefault((i & ~7, j & ~7, k & ~7), []).append((i, j, k))
    for o in leaves:
        lowers.setdefault((o[0] & ~127, o[1] & ~127, o[2] & ~127), []).append(o)
    for o in lowers:
        uppers.setdefault((o[0] & ~4095, o[1] & ~4095, o[2] & ~4095), []).append(o)
    leaf_keys, lower_keys, upper_keys = sorted(leaves), sorted(lowers), sorted(uppers)

    root_at = GRID_SIZE + TREE_SIZE
    upper_at = root_at + ROOT_SIZE + TILE_SIZE * len(upper_keys)
    lower_at = upper_at + UPPER_SIZE * len(upper_keys)
    leaf_at = lower_at + LOWER_SIZE * len(lower_keys)
    size = leaf_at + LEAF_SIZE * len(leaf_keys)
    buf = bytearray(size)

    upper_off = {o: upper_at + UPPER_SIZE * n for n, o in enumerate(upper_keys)}
    lower_off = {o: lower_at + LOWER_SIZE * n for n, o in enumerate(lower_keys)}
    leaf_off = {o: leaf_at + LEAF_SIZE * n for n, o in enumerate(leaf_keys)}

    def voxels_under(origin_, dim):
        return [c for c in voxels if all(origin_[a] <= c[a] < origin_[a] + dim for a in range(3))]

    def put_stats(at, vals):
        struct.pack_into("<4f", buf, at, *stats(vals))

    # leaves: values indexed x-major, 8^3
    for o in leaf_keys:
        at = leaf_off[o]
        cs = leaves[o]
        lo, hi = bbox(cs)
        struct.pack_into("<3i", buf, at, *lo)
        struct.pack_into("<4B", buf, at + 12, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0)
        mask = [0] * 16
        for c in cs:
            n = ((c[0] & 7) << 6) | ((c[1] & 7) << 3) | (c[2] & 7)
            set_bit(mask, n)
            struct.pack_into("<f", buf, at + LEAF_TABLE + 4 * n, voxels[c])
        struct.pack_into("<16I", buf, at + 16, *mask)
        put_stats(at + LEAF_STATS, [voxels[c] for c in cs])

    def internal(at, node_origin, dim, children, child_off, log2_child, stats_at, table_at,
                 mask_words, child_mask_at):
        cs = voxels_under(node_origin, dim)
        lo, hi = bbox(cs)
        struct.pack_into("<3i3i", buf, at, *(lo + hi))
        child_mask = [0] * mask_words
        log2 = {128: 4, 4096: 5}[dim]
        for c in children:
            n = 0
            for a in range(3):
                n = (n << log2) | (((c[a] - node_origin[a]) >> log2_child) & ((1 << log2) - 1))
            set_bit(child_mask, n)
            struct.pack_into("<q", buf, at + table_at + 8 * n, child_off[c] - at)
        struct.pack_into("<%dI" % mask_words, buf, child_mask_at, *child_mask)
        put_stats(at + stats_at, [voxels[c] for c in cs])

    for o in lower_keys:
        internal(lower_off[o], o, 128, lowers[o], leaf_off, 3, LOWER_STATS, LOWER_TABLE, 128,
                 lower_off[o] + 544)
    for o in upper_keys:
        internal(upper_off[o], o, 4096, uppers[o], lower_off, 7, UPPER_STATS, UPPER_TABLE, 1024,
                 upper_off[o] + 4128)

    # root and its tiles: keys of the upper nodes' origins, children at
    # offsets from the root
    lo, hi = bbox(list(voxels))
    struct.pack_into("<3i3iI", buf, root_at, *(lo + hi), len(upper_keys))
    struct.pack_into("<f", buf, root_at + 28, 0.0)  # background
    put_stats(root_at + 32, list(voxels.values()))
    for n, o in enumerate(upper_keys):
        key = (o[2] >> 12) | ((o[1] >> 12) << 21) | ((o[0] >> 12) << 42)
        struct.pack_into("<QqIf", buf, root_at + ROOT_SIZE + TILE_SIZE * n, key,
                         upper_off[o] - root_at, 0, 0.0)

    # tree: node offsets from the tree, counts
    tree_at = GRID_SIZE

    def first(keys, off):
        return off[keys[0]] - tree_at if keys else 0
    struct.pack_into("<4Q6IQ", buf, tree_at, first(leaf_keys, leaf_off),
                     first(lower_keys, lower_off), first(upper_keys, upper_off),
                     root_at - tree_at, len(leaf_keys), len(lower_keys), len(upper_keys),
                     0, 0, 0, len(voxels))

    # grid: header, name, map, bounds
    vs = voxel_size
    wlo = [vs * lo[a] + origin[a] for a in range(3)]
    whi = [vs * (hi[a] + 1) + origin[a] for a in range(3)]
    struct.pack_into("<QQIIIIQ", buf, 0, MAGIC, 0xFFFFFFFFFFFFFFFF, VERSION, FLAGS, 0, 1, size)
    nb = name.encode()
    buf[40:40 + len(nb)] = nb
    mat = [vs, 0, 0, 0, vs, 0, 0, 0, vs]
    inv = [1 / vs, 0, 0, 0, 1 / vs, 0, 0, 0, 1 / vs]
    struct.pack_into("<9f9f3ff", buf, 296, *(mat + inv + list(origin) + [1.0]))
    struct.pack_into("<9d9d3dd", buf, 296 + 88, *(mat + inv + list(origin) + [1.0]))
    struct.pack_into("<6d3dIIqI", buf, 560, *(wlo + whi + [vs, vs, vs]),
                     GRID_CLASS_FOG_VOLUME, GRID_TYPE_FLOAT, 0, 0)
    meta = dict(size=size, voxels=len(voxels), wbox=wlo + whi, ibox=lo + hi, vs=vs,
                nodes=(len(leaf_keys), len(lower_keys), len(upper_keys), 1))
    return bytes(buf), meta


def string_hash(s):
    h = 0
    for ch in s.encode():
        overflow = h >> 56
        h = (h * 67 + ch + overflow) & 0xFFFFFFFFFFFFFFFF
    return h


def write_file(path, grids, codec):
    """grids: [(name, buffer, meta)], one segment."""
    blobs = []
    for name, data, meta in grids:
        if codec == CODEC["zip"]:
            z = zlib.compress(data, 9)
            blobs.append(struct.pack("<Q", len(z)) + z)
        else:
            blobs.append(data)
    out = bytearray(struct.pack("<QIHH", MAGIC, VERSION, len(grids), codec))
    for (name, data, meta), blob in zip(grids, blobs):
        nb = name.encode() + b"\0"
        out += struct.pack("<QQQQII6d6i3dI4I3IHHI", meta["size"], len(blob), string_hash(name),
                           meta["voxels"], GRID_TYPE_FLOAT, GRID_CLASS_FOG_VOLUME,
                           *meta["wbox"], *meta["ibox"], meta["vs"], meta["vs"], meta["vs"],
                           len(nb), *meta["nodes"], 0, 0, 0, codec, 0, VERSION)
        out += nb
    for blob in blobs:
        out += blob
    with open(path, "wb") as f:
        f.write(out)


def main():
    codec = "zip"
    if len(sys.argv) == 3 and sys.argv[1] == "--codec" and sys.argv[2] in CODEC:
        codec = sys.argv[2]
    elif len(sys.argv) != 1:
        sys.exit("usage: make_nanovdb.py [--codec none|zip]")
    # density: a lumpy blob over 12 x 10 x 8 voxels from (3, 5, 2), not
    # aligned to the 8^3 leaves, dense up to its faces (so that the
    # bounds' half-voxel placement shows), with a few inactive holes
    density = {}
    for i in range(3, 15):
        for j in range(5, 15):
            for k in range(2, 10):
                if (i * 7 + j * 3 + k) % 23 == 0:
                    continue
                u, v, w = (i - 8.5) / 6, (j - 9.5) / 5, (k - 5.5) / 4
                d = 1.4 * math.exp(-1.2 * (u * u + v * v + w * w)) + 0.35 * (1 + math.sin(1.3 * i + 0.7 * j - 0.9 * k))
                density[(i, j, k)] = round(d, 4)
    # temperature: a hot core over a smaller box that pokes out of the
    # density's bounds on top (the medium's bounds are the union)
    temperature = {}
    for i in range(6, 12):
        for j in range(9, 17):
            for k in range(4, 8):
                temperature[(i, j, k)] = round(2600 + 260 * ((i + 2 * j + k) % 5) + 90 * (j - 9), 2)
    vs, origin = 0.15, (-1.3, -0.5, -0.8)
    grids = []
    for name, vox in (("density", density), ("temperature", temperature)):
        data, meta = grid_buffer(name, vox, vs, origin)
        grids.append((name, data, meta))
    path = "vol_nanovdb.nvdb" if codec == "zip" else "vol_nanovdb_raw.nvdb"
    write_file(os.path.join(HERE, path), grids, CODEC[codec])


if __name__ == "__main__":
    main()
