#!/usr/bin/env python3
"""Writes tests/data/pbrt_layered_albedo.toml: the directional albedo of pbrt-v4's layered
materials as pbrt-v4 itself computes it, for tests/layered.rs.

A flat square of the material fills an orthographic view at cos θ = `cos` from its normal,
lit by a uniform source of radiance 1 at every wavelength (pixel Y = the albedo, the material
being grey):
- `sampled`: a uniform `infinite` light, `path` integrator of `maxdepth` 1. pbrt-v4 lights a
  uniform sky by BSDF sampling alone, so this is the albedo its `LayeredBxDF::Sample_f` gives;
- `evaluated`: a sphere area light around everything, `simplepath` with light sampling, so the
  albedo its `LayeredBxDF::f` gives (rough coatings only: a smooth coating's delta reflection
  takes another route there).
Each figure is the mean over 8 × 8 pixels at 4096 spp with its standard error.

Usage: build pbrt-v4 (../shared/tools/pbrt/build_pbrt.sh), pip install numpy OpenImageIO;
python3 scripts/gen_pbrt_layered_albedo.py
"""
import math
import os
import subprocess
import tempfile

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PBRT = os.environ.get("PBRT", os.path.expanduser("~/.cache/pbrt-v4/bin/pbrt"))
SPP = 4096

# (name, pbrt material, spectrace parameters)
MATERIALS = [
    ("diffuse_rough", 'Material "coateddiffuse" "spectrum reflectance" [300 0.5 900 0.5] "float roughness" 0.05',
     {"base": "diffuse", "rho": 0.5, "eta": 1.5, "alpha": 0.05 ** 0.5, "thickness": 0.01, "albedo": 0.0, "g": 0.0}),
    ("diffuse_scattering", 'Material "coateddiffuse" "spectrum reflectance" [300 0.8 900 0.8] "float roughness" 0.1 '
     '"spectrum albedo" [300 0.7 900 0.7] "float g" 0.3 "float thickness" 0.3 "float eta" 1.33',
     {"base": "diffuse", "rho": 0.8, "eta": 1.33, "alpha": 0.1 ** 0.5, "thickness": 0.3, "albedo": 0.7, "g": 0.3}),
    ("conductor_rough", 'Material "coatedconductor" "float interface.roughness" 0.02 '
     '"spectrum conductor.eta" [300 0.2 900 0.2] "spectrum conductor.k" [300 3 900 3] "float conductor.roughness" 0.1',
     {"base": "conductor", "n": 0.2, "k": 3.0, "conductor_alpha": 0.1 ** 0.5, "eta": 1.5, "alpha": 0.02 ** 0.5,
      "thickness": 0.01, "albedo": 0.0, "g": 0.0}),
]
COS = [0.9, 0.5, 0.2]


def render(tmp, text):
    scene = os.path.join(tmp, "a.pbrt")
    with open(scene, "w") as f:
        f.write(text)
    exr = os.path.join(tmp, "a.exr")
    subprocess.run([PBRT, "--quiet", "--outfile", exr, scene], check=True, cwd=tmp)
    i = oiio.ImageInput.open(exr)
    a = np.array(i.read_image(format="float"))
    i.close()
    y = 0.2126 * a[..., 0] + 0.7152 * a[..., 1] + 0.0722 * a[..., 2]
    return float(y.mean()), float(y.std() / math.sqrt(y.size))


def scene(mat, tilt, evaluated):
    if evaluated:
        integ = 'Integrator "simplepath" "integer maxdepth" 1 "bool samplelights" true "bool samplebsdf" true'
        light = ('AttributeBegin\nAreaLightSource "diffuse" "spectrum L" [300 1 900 1]\nReverseOrientation\n'
                 'Shape "sphere" "float radius" 1000\nAttributeEnd\n')
    else:
        integ = 'Integrator "path" "integer maxdepth" 1'
        light = 'LightSource "infinite" "spectrum L" [300 1 900 1]\n'
    return f"""LookAt 0 0 10  0 0 0  0 1 0
Camera "orthographic"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
Sampler "zsobol" "integer pixelsamples" {SPP}
{integ}
WorldBegin
{light}Rotate {tilt} 1 0 0
{mat}
Shape "trianglemesh" "point3 P" [-50 -50 0 50 -50 0 50 50 0 -50 50 0] "integer indices" [0 1 2 0 2 3]
"""


def main():
    out = ["# Written by scripts/gen_pbrt_layered_albedo.py with pbrt-v4 (mmp/pbrt-v4 5f7a6068):",
           "# directional albedos of its layered materials, through its sampler and through its f.", ""]
    with tempfile.TemporaryDirectory() as tmp:
        for name, mat, params in MATERIALS:
            for c in COS:
                tilt = math.degrees(math.acos(c))
                s, se = render(tmp, scene(mat, tilt, False))
                e, ee = render(tmp, scene(mat, tilt, True))
                print(name, c, s, se, e, ee)
                out += ["[[case]]", f'name = "{name}"', f"cos = {c}",
                        "params = { " + ", ".join(f'{k} = {v!r}' if not isinstance(v, str) else f'{k} = "{v}"'
                                                  for k, v in params.items()) + " }",
                        f"sampled = {s:.6g}", f"sampled_se = {se:.3g}",
                        f"evaluated = {e:.6g}", f"evaluated_se = {ee:.3g}", ""]
    with open(os.path.join(ROOT, "tests", "data", "pbrt_layered_albedo.toml"), "w") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main()
