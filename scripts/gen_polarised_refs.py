#!/usr/bin/env python3
"""References for Mitsuba 3's polarisation documentation scenes (issue 28), rendered by Mitsuba
3.9.1 `scalar_spectral_polarized`:

    pip install mitsuba==3.9.1 OpenImageIO && python3 scripts/gen_polarised_refs.py [scene ...]

The scenes are mitsuba-data's, copied unchanged into tests/reference/mitsuba-data/docs/scenes/
(see its README). Two rewrites, which tests/polarised_reference.rs applies identically:
- the includes (`include/shape_scene.xml` of the polariser scenes, `include/matpreview.xml` and
  `matpreview_stokes.xml` of the pplastic scenes): the film 960 × 720 becomes WIDTH × HEIGHT,
  and an integrator not yet inside Mitsuba's `stokes` integrator is wrapped in one, so that the
  references hold S1–S3 besides S0 (the image the scene renders as it stands is S0);
- `integrator_stokes_cbox.xml` is loaded with `res` = CBOX_RES (its own parameter);
- the four `measured_polarized` scenes read tests/reference/pbsdf/synthetic.pbsdf in place of
  the KAIST data their `filename` names (not distributed with mitsuba-data).

For each scene it renders SEEDS independent images of SPP samples per pixel and writes, in
tests/reference/polarised/<scene>/stats.txt, `key = value` lines: spp, seeds, sizes, and per
tile of TILE × TILE pixels the means of the XYZ of S0, S1, S2, S3 (12 numbers: Mitsuba's
`stokes` AOVs, linear sRGB, read back to XYZ with its own sRGB → XYZ matrix) followed by
their 12 standard errors from the spread of the seeds.
"""
import os
import re
import sys
import tempfile
import time

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_spectral_polarized")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS = os.path.join(ROOT, "tests", "reference", "mitsuba-data", "docs", "scenes")
OUT = os.path.join(ROOT, "tests", "reference", "polarised")
SCENES = ["bsdf_polarizer_middle", "bsdf_polarizer_aligned", "bsdf_polarizer_absorbing",
          "integrator_stokes_cbox", "bsdf_pplastic", "bsdf_pplastic_diffuse",
          "bsdf_pplastic_diffuse_stokes", "bsdf_pplastic_specular", "bsdf_pplastic_specular_stokes",
          "bsdf_measured_polarized_gold", "bsdf_measured_polarized_gold_stokes",
          "bsdf_measured_polarized_fakegold", "bsdf_measured_polarized_fakegold_stokes"]
# the measured_polarized scenes' KAIST data (pbsdfs/6_gold_inpainted.pbsdf, ...) are not in
# mitsuba-data; their references use this synthetic table instead (scripts/gen_pbsdf_vectors.py)
SYNTHETIC = os.path.join(ROOT, "tests", "reference", "pbsdf", "synthetic.pbsdf")
INCLUDES = ["shape_scene.xml", "matpreview.xml", "matpreview_stokes.xml"]
WIDTH, HEIGHT, CBOX_RES = 120, 90, 128
TILE = 30
CBOX_TILE = 32
SPP = 256
SEEDS = 8
SRGB_TO_XYZ = np.array(
    [[0.412453, 0.357580, 0.180423], [0.212671, 0.715160, 0.072169], [0.019334, 0.119193, 0.950227]]
)


def stokes_include(text):
    """The include with the film reduced and its integrator inside `stokes` (see the doc)."""
    text = re.sub(r'name="width" value="960"', f'name="width" value="{WIDTH}"', text)
    text = re.sub(r'name="height" value="720"', f'name="height" value="{HEIGHT}"', text)
    if 'type="stokes"' in text:
        return text
    return re.sub(r'(<integrator type="[^"]*"\s*/>|<integrator type="[^"]*">.*?</integrator>)',
                  r'<integrator type="stokes">\1</integrator>', text, count=1, flags=re.S)


def render(name, inc_names):
    params = {}
    if name == "integrator_stokes_cbox":
        path, params, tile = os.path.join(DOCS, name + ".xml"), {"res": CBOX_RES}, CBOX_TILE
        tmp = None
    else:
        with open(os.path.join(DOCS, name + ".xml")) as f:
            text = f.read()
        for inc, tmp_name in inc_names.items():
            text = text.replace("include/" + inc, "include/" + tmp_name)
        text = re.sub(r'pbsdfs/[^"]+\.pbsdf', SYNTHETIC, text)
        tmp = path = os.path.join(DOCS, "_tmp_" + name + ".xml")
        with open(path, "w") as f:
            f.write(text)
        tile = TILE
    try:
        scene = mi.load_file(path, **params)
        film = scene.sensors()[0].film()
        imgs = []
        for seed in range(SEEDS):
            t = time.time()
            img = np.array(mi.render(scene, seed=seed, spp=SPP), dtype=np.float64)
            if seed == 0:
                names = [f.name for f in film.bitmap().struct_()]
            xyz = []
            for k in range(4):
                rgb = img[..., [names.index(f"S{k}.{c}") for c in "RGB"]]
                xyz.append(rgb @ SRGB_TO_XYZ.T)
            imgs.append(np.concatenate(xyz, axis=-1))  # H × W × 12
            print(f"{name}: seed {seed}, {time.time() - t:.1f} s", flush=True)
    finally:
        if tmp:
            os.remove(tmp)
    imgs = np.stack(imgs)
    h, w = imgs.shape[1:3]
    lines = [f"mitsuba = {mi.__version__}", "variant = scalar_spectral_polarized", f"spp = {SPP}",
             f"seeds = {SEEDS}", f"width = {w}", f"height = {h}", f"tile = {tile}"]
    for ty in range(h // tile):
        for tx in range(w // tile):
            per_seed = imgs[:, ty * tile:(ty + 1) * tile, tx * tile:(tx + 1) * tile, :].mean(axis=(1, 2))
            m = per_seed.mean(axis=0)
            se = per_seed.std(axis=0, ddof=1) / np.sqrt(SEEDS)
            lines.append(f"tile_{tx}_{ty} = " + " ".join(f"{v:.8g}" for v in (*m, *se)))
    out = os.path.join(OUT, name)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "stats.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {out}", flush=True)


def main():
    global SPP, SEEDS
    if os.environ.get("QUICK"):
        SPP, SEEDS = 4, 2
    tmp = {}
    try:
        for inc in INCLUDES:
            with open(os.path.join(DOCS, "include", inc)) as f:
                include = stokes_include(f.read())
            fd, inc_path = tempfile.mkstemp(suffix=".xml", dir=os.path.join(DOCS, "include"))
            with os.fdopen(fd, "w") as f:
                f.write(include)
            tmp[inc] = inc_path
        for name in sys.argv[1:] or SCENES:
            render(name, {k: os.path.basename(v) for k, v in tmp.items()})
    finally:
        for v in tmp.values():
            os.remove(v)


if __name__ == "__main__":
    main()
