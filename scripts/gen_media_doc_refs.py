#!/usr/bin/env python3
"""References for Mitsuba 3's two documentation media scenes (a bunny of subsurface-scattering
material, `docs/scenes/medium_homogeneous_sss.xml` and `_textured.xml` of mitsuba-data, copied
unchanged into tests/reference/mitsuba-data/docs/scenes/), rendered by Mitsuba 3.9.1
`scalar_spectral` at a reduced film (their include's 960 × 720 becomes WIDTH × HEIGHT; nothing
else changes):

    pip install mitsuba==3.9.1 OpenImageIO && python3 scripts/gen_media_doc_refs.py

For each scene it renders SEEDS independent images of SPP samples per pixel and writes, in
tests/reference/media_docs/<scene>/:

    ref.exr     float32 X, Y, Z: the mean of the seeds (Mitsuba's RGB film read back to XYZ
                with its own sRGB → XYZ matrix)
    stats.txt   `key = value`: spp, seeds, and per tile of TILE × TILE pixels the mean of X, Y,
                Z and its standard error from the spread of the seeds

tests/media_reference.rs renders the same scenes (the include rewritten the same way) and holds
spectrace's tile means to these within 5 combined standard errors.
"""
import os
import re
import sys
import tempfile
import time

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_spectral")
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "reference", "mitsuba-data")
OUT = os.path.join(ROOT, "tests", "reference", "media_docs")
SCENES = ["medium_homogeneous_sss", "medium_homogeneous_sss_textured"]
WIDTH, HEIGHT = 120, 90
TILE = 30
SPP = 512
SEEDS = 8
SRGB_TO_XYZ = np.array(
    [[0.412453, 0.357580, 0.180423], [0.212671, 0.715160, 0.072169], [0.019334, 0.119193, 0.950227]]
)


def small_include(text):
    """The include with the film reduced (the only change)."""
    text = re.sub(r'name="width" value="960"', f'name="width" value="{WIDTH}"', text)
    return re.sub(r'name="height" value="720"', f'name="height" value="{HEIGHT}"', text)


def main():
    docs = os.path.join(DATA, "docs", "scenes")
    with open(os.path.join(docs, "include", "shape_scene.xml")) as f:
        include = small_include(f.read())
    # a copy of the include beside the original, so the scenes' relative paths stay valid
    fd, inc_path = tempfile.mkstemp(suffix=".xml", dir=os.path.join(docs, "include"))
    with os.fdopen(fd, "w") as f:
        f.write(include)
    try:
        for name in sys.argv[1:] or SCENES:
            with open(os.path.join(docs, name + ".xml")) as f:
                text = f.read().replace("include/shape_scene.xml", "include/" + os.path.basename(inc_path))
            path = os.path.join(docs, "_tmp_" + name + ".xml")
            with open(path, "w") as f:
                f.write(text)
            try:
                scene = mi.load_file(path)
                imgs = []
                for seed in range(SEEDS):
                    t = time.time()
                    rgb = np.array(mi.render(scene, seed=seed, spp=SPP), dtype=np.float64)[..., :3]
                    imgs.append(rgb @ SRGB_TO_XYZ.T)
                    print(f"{name}: seed {seed}, {time.time() - t:.1f} s", flush=True)
            finally:
                os.remove(path)
            imgs = np.stack(imgs)
            mean = imgs.mean(axis=0).astype(np.float32)
            out = os.path.join(OUT, name)
            os.makedirs(out, exist_ok=True)
            spec = oiio.ImageSpec(WIDTH, HEIGHT, 3, "float")
            spec.channelnames = ("X", "Y", "Z")
            o = oiio.ImageOutput.create(os.path.join(out, "ref.exr"))
            o.open(os.path.join(out, "ref.exr"), spec)
            o.write_image(mean)
            o.close()
            lines = [f"mitsuba = {mi.__version__}", "variant = scalar_spectral", f"spp = {SPP}",
                     f"seeds = {SEEDS}", f"width = {WIDTH}", f"height = {HEIGHT}", f"tile = {TILE}"]
            for ty in range(HEIGHT // TILE):
                for tx in range(WIDTH // TILE):
                    block = imgs[:, ty * TILE:(ty + 1) * TILE, tx * TILE:(tx + 1) * TILE, :]
                    per_seed = block.mean(axis=(1, 2))  # seeds × 3
                    m = per_seed.mean(axis=0)
                    se = per_seed.std(axis=0, ddof=1) / np.sqrt(SEEDS)
                    lines.append(f"tile_{tx}_{ty} = " + " ".join(f"{v:.8g}" for v in (*m, *se)))
            with open(os.path.join(out, "stats.txt"), "w") as f:
                f.write("\n".join(lines) + "\n")
            print(f"wrote {out}", flush=True)
    finally:
        os.remove(inc_path)


if __name__ == "__main__":
    main()
