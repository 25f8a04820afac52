#!/usr/bin/env python3
"""Writes a height-field mesh for benchmarks: an n x n vertex grid over [-1, 1]^2 (m) with
height 0.15·sin(5x)·cos(4y) + 0.05·sin(23x + 17y), as binary little-endian PLY (no normals),
2 (n - 1)^2 triangles, or as a Wavefront OBJ when OUT ends in .obj. Standard library only.

    python3 scripts/gen_heightfield.py [N] [OUT.ply|OUT.obj]   (default 709 -> 1,002,528 triangles)
    python3 scripts/gen_heightfield.py 2238 benchmarks/scenes/heightfield10m.ply   (10,008,338)
"""
import math
import struct
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 709
out = sys.argv[2] if len(sys.argv) > 2 else "benchmarks/scenes/heightfield.ply"
nv, nf = n * n, 2 * (n - 1) ** 2


def height(x: float, y: float) -> float:
    return 0.15 * math.sin(5 * x) * math.cos(4 * y) + 0.05 * math.sin(23 * x + 17 * y)


if out.endswith(".obj"):
    with open(out, "w") as f:
        f.write(f"# height field, {nv} vertices, {nf} triangles (scripts/gen_heightfield.py)\n")
        for j in range(n):
            y = -1 + 2 * j / (n - 1)
            f.write("".join(
                f"v {x:.7g} {height(x, y):.7g} {y:.7g}\n"
                for x in (-1 + 2 * i / (n - 1) for i in range(n))
            ))
        for j in range(n - 1):
            lines = []
            for i in range(n - 1):
                a = j * n + i + 1  # OBJ indices start at 1
                lines.append(f"f {a} {a + n} {a + 1}\nf {a + 1} {a + n} {a + n + 1}\n")
            f.write("".join(lines))
    print(f"{out}: {nv} vertices, {nf} triangles")
    sys.exit(0)

with open(out, "wb") as f:
    f.write(
        (
            "ply\nformat binary_little_endian 1.0\n"
            f"element vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n"
            f"element face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
        ).encode()
    )
    buf = bytearray()
    for j in range(n):
        y = -1 + 2 * j / (n - 1)
        for i in range(n):
            x = -1 + 2 * i / (n - 1)
            z = height(x, y)
            buf += struct.pack("<3f", x, z, y)
    f.write(buf)
    buf = bytearray()
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            buf += struct.pack("<B3i", 3, a, a + n, a + 1)
            buf += struct.pack("<B3i", 3, a + 1, a + n, a + n + 1)
    f.write(buf)
print(f"{out}: {nv} vertices, {nf} triangles")
