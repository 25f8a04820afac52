#!/usr/bin/env python3
"""Renders the pbrt-v4 reference scenes (tests/reference/pbrt/<name>/scene.pbrt) with pbrt-v4
and writes each folder's refs.toml, which tests/pbrt_reference.rs holds spectrace to.

For every 8 × 8 block of pixels: the mean Y = 0.2126 R + 0.7152 G + 0.0722 B (pbrt-v4's film:
Y = ∫ȳ·L dλ) of two renders with seeds 1 and 2, and its standard error from the pixels'
differences between the seeds (√Σ(a − b)² / 2n, the pixels taken as independent).

It also writes goniometric/gonio.png, alpha/cutout.png, imagemap/tex.png and quad_st.ply, bump/normal.png, gold_equal_area/eqarea.exr and glass_machines/sky.exr (the map of
scripts/gen_pbrt_refs.py, the latter without its glow) and
killeroo_style/geometry/blob.pbrt: a `loopsubdiv` control mesh (an icosahedron,
its vertices moved by a fixed pseudo-random amount), the stand-in for the killeroo model of
pbrt-v4-scenes' killeroo-simple.pbrt, whose layout the scene copies.

A folder whose compare.toml says `sensor = true` gets R, G and B blocks instead of Y.

Usage: build pbrt-v4 (../shared/tools/pbrt/build_pbrt.sh), pip install numpy OpenImageIO;
python3 scripts/gen_pbrt_reference.py [name ...]
"""
import math
import os
import random
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "tests", "reference", "pbrt")
PBRT = os.environ.get("PBRT", os.path.expanduser("~/.cache/pbrt-v4/bin/pbrt"))
BLOCK = 8


def blob():
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    rng = random.Random(32)
    r = 65 / math.sqrt(1 + t * t)
    pts = []
    for x, y, z in v:
        k = r * rng.uniform(0.75, 1.25)
        pts.append((k * x, 25 + k * 1.3 * y, -70 + k * 0.9 * z))
    lines = ['# written by scripts/gen_pbrt_reference.py: an icosahedron moved at random (seed 32)',
             'Shape "loopsubdiv"', '    "integer levels" [ 3 ]',
             '    "point3 P" [ ' + "  ".join(" ".join(f"{c:.4f}" for c in p) for p in pts) + " ]",
             '    "integer indices" [ ' + "  ".join(" ".join(str(i) for i in tri) for tri in f) + " ]", ""]
    with open(os.path.join(BASE, "killeroo_style", "geometry", "blob.pbrt"), "w") as out:
        out.write("\n".join(lines))


def write_tiles(path):
    """An 8-bit sRGB texture of 16 × 8 pixels: coloured tiles and an asymmetric mark."""
    img = np.zeros((8, 16, 3), np.uint8)
    for y in range(8):
        for x in range(16):
            img[y, x] = [40 + 13 * x, 60 + 20 * y, 220 - 9 * x - 8 * y]
    for x, y in [(2, 1), (2, 2), (2, 3), (3, 1), (4, 1), (3, 3), (2, 4), (2, 5)]:
        img[y, x] = [250, 250, 240]
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(16, 8, 3, "uint8"))
    out.write_image(img)
    out.close()


def read_y(path, rgb=False):
    """Y of pbrt-v4's image or, with `rgb`, its R, G and B stacked one above the other."""
    i = oiio.ImageInput.open(path)
    a = np.array(i.read_image(format="float")).astype(np.float64)
    i.close()
    if rgb:
        return np.concatenate([a[..., 0], a[..., 1], a[..., 2]], axis=0)
    return 0.2126 * a[..., 0] + 0.7152 * a[..., 1] + 0.0722 * a[..., 2]


def blocks(a, b):
    h, w = a.shape
    mean, se = [], []
    for by in range(0, h, BLOCK):
        for bx in range(0, w, BLOCK):
            pa, pb = a[by:by + BLOCK, bx:bx + BLOCK], b[by:by + BLOCK, bx:bx + BLOCK]
            n = pa.size
            mean.append(float((pa + pb).mean() / 2))
            se.append(float(np.sqrt(((pa - pb) ** 2).sum()) / (2 * n)))
    return mean, se


def write_normal_map(path):
    """normal.png: an 8-bit tangent-space normal map, stored linearly as (n + 1)/2 (pbrt-v4 reads
    normal maps with a linear encoding), of tilted facets in rows: the normal leans along +u in
    one half of each period and along +v in the other."""
    n = 64
    img = np.zeros((n, n, 3), np.float64)
    for y in range(n):
        for x in range(n):
            t = 0.35 * math.sin(2 * math.pi * (x + 0.5) / n)
            nv = np.array([t, 0.2 if y < n // 2 else -0.1, 1.0])
            img[y, x] = (nv / np.linalg.norm(nv) + 1) / 2
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(n, n, 3, "uint8"))
    out.write_image((img * 255 + 0.5).astype(np.uint8))
    out.close()


def write_st_quad(path):
    """quad_st.ply: an ASCII PLY square whose texture coordinates are named texture_s and
    texture_t (names pbrt-v4's PLY reader takes), rotated in uv so that a lookup that ignored
    them would show."""
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                "property float z\nproperty float texture_s\nproperty float texture_t\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "-3.5 0.01 0.5 1 0\n-1.5 0.01 0.5 1 1\n-1.5 0.01 2.5 0 1\n-3.5 0.01 2.5 0 0\n"
                "4 0 1 2 3\n")


def write_cutout(path):
    """cutout.png: an 8-bit grey alpha mask: white (opaque) with black round holes and a grey
    band (partly transparent)."""
    n = 64
    img = np.ones((n, n), np.float64)
    for y in range(n):
        for x in range(n):
            fx, fy = (x % 16) - 7.5, (y % 16) - 7.5
            if fx * fx + fy * fy < 25:
                img[y, x] = 0.0
            if 40 <= y < 48:
                img[y, x] = 0.6
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(n, n, 1, "uint8"))
    out.write_image((img * 255 + 0.5).astype(np.uint8)[..., None])
    out.close()


def write_goniometric(path):
    """gonio.png: a 64 × 64 8-bit sRGB image in the equal-area octahedral layout for the
    goniometric light: a bright lobe off the centre, a dim floor, a brighter band at small u,
    and channels that differ (pbrt-v4 lights with their mean)."""
    n = 64
    img = np.zeros((n, n, 3), np.float64)
    for y in range(n):
        for x in range(n):
            u, v = (x + 0.5) / n, (y + 0.5) / n
            g = 0.1 + 0.8 * math.exp(-((u - 0.5) ** 2 + (v - 0.6) ** 2) / 0.02) + (0.3 if u < 0.3 else 0.0)
            img[y, x] = [min(1.0, 1.2 * g), g, 0.6 * g]
    enc = np.where(img <= 0.0031308, 12.92 * img, 1.055 * img ** (1 / 2.4) - 0.055)
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(n, n, 3, "uint8"))
    out.write_image((enc * 255 + 0.5).astype(np.uint8))
    out.close()


def main():
    blob()
    write_goniometric(os.path.join(BASE, "goniometric", "gonio.png"))
    write_cutout(os.path.join(BASE, "alpha", "cutout.png"))
    write_st_quad(os.path.join(BASE, "imagemap", "quad_st.ply"))
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from gen_pbrt_refs import write_equal_area_map
    write_tiles(os.path.join(BASE, "imagemap", "tex.png"))
    write_normal_map(os.path.join(BASE, "bump", "normal.png"))
    write_equal_area_map(os.path.join(BASE, "gold_equal_area", "eqarea.exr"))
    # without the glow: a small bright source seen through glass on a diffuse floor makes
    # caustics whose rare, bright samples no two-seed estimate of the noise can bound
    write_equal_area_map(os.path.join(BASE, "glass_machines", "sky.exr"), glow=False)
    names = sys.argv[1:] or sorted(d for d in os.listdir(BASE) if os.path.isfile(os.path.join(BASE, d, "scene.pbrt")))
    for name in names:
        folder = os.path.join(BASE, name)
        compare = os.path.join(folder, "compare.toml")
        # a film with a pixel sensor: R, G and B compared channel by channel
        rgb = os.path.isfile(compare) and "sensor = true" in open(compare).read()
        with tempfile.TemporaryDirectory() as tmp:
            imgs = []
            for seed in (1, 2):
                exr = os.path.join(tmp, f"{seed}.exr")
                subprocess.run([PBRT, "--quiet", "--seed", str(seed), "--outfile", exr,
                                os.path.join(folder, "scene.pbrt")], check=True, cwd=folder)
                imgs.append(read_y(exr, rgb))
        mean, se = blocks(*imgs)
        h, w = imgs[0].shape
        h = h // 3 if rgb else h
        print(name, w, h, float((imgs[0] + imgs[1]).mean() / 2))
        with open(os.path.join(folder, "refs.toml"), "w") as out:
            out.write("\n".join([
                "# Written by scripts/gen_pbrt_reference.py with pbrt-v4 (mmp/pbrt-v4 5f7a6068): per",
                f"# {BLOCK} × {BLOCK} block (row-major), the mean Y of seeds 1 and 2 and its standard error"
                + (" (R, G, B:\n# every block of R, then of G, then of B)." if rgb else "."),
                f"width = {w}", f"height = {h}", f"block = {BLOCK}",
                "mean = [" + ", ".join(f"{m:.7g}" for m in mean) + "]",
                "stderr = [" + ", ".join(f"{s:.4g}" for s in se) + "]", ""]))


if __name__ == "__main__":
    main()
