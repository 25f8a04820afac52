#!/usr/bin/env python3
"""Writes the Mitsuba `.serialized` meshes of tests/reference/serialized/ (standard library
only), then loads each with Mitsuba 3.9.1 and prints what Mitsuba read, the truth that
tests/geometry_serialized.rs asserts:

- meshes.serialized, version 4, two meshes:
  0: a unit square in z = 0 as 2 triangles, float32 positions and vertex normals (0, 0, 1);
  1: a 16 × 16-quad height field over [-1, 1]² (y up), float64 positions, uvs, no normals
     (Mitsuba computes smooth normals); 289 vertices, 512 triangles;
- quad_v3.serialized, version 3, one mesh: a 2 × 1 rectangle in z = 0, float32, uvs.

Usage: python3 scripts/gen_serialized.py [--check]   (--check needs pip install mitsuba==3.9.1)
"""
import math
import os
import struct
import sys
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "reference", "serialized")


def mesh_bytes(version, name, pos, tris, normals=None, uvs=None, double=False):
    flags = (0x1 if normals else 0) | (0x2 if uvs else 0) | (0x2000 if double else 0x1000)
    f = "d" if double else "f"
    body = struct.pack("<I", flags)
    if version == 4:
        body += name.encode() + b"\0"
    body += struct.pack("<QQ", len(pos), len(tris))
    for p in pos:
        body += struct.pack("<3" + f, *p)
    for n in normals or []:
        body += struct.pack("<3" + f, *n)
    for t in uvs or []:
        body += struct.pack("<2" + f, *t)
    for t in tris:
        body += struct.pack("<3I", *t)
    return struct.pack("<HH", 0x041C, version) + zlib.compress(body)


def file_bytes(version, meshes):
    out, offsets = b"", []
    for m in meshes:
        offsets.append(len(out))
        out += m
    if version == 4:
        out += b"".join(struct.pack("<Q", o) for o in offsets)
    else:
        out += b"".join(struct.pack("<I", o) for o in offsets)
    return out + struct.pack("<I", len(meshes))


def heightfield(n=16):
    pos, uvs, tris = [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x, z = -1 + 2 * i / n, -1 + 2 * j / n
            pos.append((x, 0.15 * math.sin(3 * x) * math.cos(2 * z), z))
            uvs.append((i / n, j / n))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            tris += [(a, a + n + 1, a + 1), (a + 1, a + n + 1, a + n + 2)]
    return pos, uvs, tris


def main():
    os.makedirs(OUT, exist_ok=True)
    square = mesh_bytes(4, "square", [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
                        [(0, 1, 2), (0, 2, 3)], normals=[(0, 0, 1)] * 4)
    pos, uvs, tris = heightfield()
    hf = mesh_bytes(4, "heightfield", pos, tris, uvs=uvs, double=True)
    with open(os.path.join(OUT, "meshes.serialized"), "wb") as f:
        f.write(file_bytes(4, [square, hf]))
    quad = mesh_bytes(3, "", [(-1, -0.5, 0), (1, -0.5, 0), (1, 0.5, 0), (-1, 0.5, 0)],
                      [(0, 1, 2), (0, 2, 3)], uvs=[(0, 0), (1, 0), (1, 1), (0, 1)])
    with open(os.path.join(OUT, "quad_v3.serialized"), "wb") as f:
        f.write(file_bytes(3, [quad]))
    print("wrote", OUT)
    if "--check" in sys.argv:
        import mitsuba as mi
        mi.set_variant("scalar_spectral")
        for fn, idx in [("meshes.serialized", 0), ("meshes.serialized", 1), ("quad_v3.serialized", 0)]:
            m = mi.load_dict({"type": "serialized", "filename": os.path.join(OUT, fn), "shape_index": idx})
            print(fn, idx, "vertices", m.vertex_count(), "faces", m.face_count(),
                  "bbox", list(m.bbox().min), list(m.bbox().max), "area", round(m.surface_area(), 6),
                  "normals", m.has_vertex_normals(), "uvs", m.has_vertex_texcoords())


main()
