#!/usr/bin/env python3
"""Writes tests/data/hair_eval.toml: values and densities of Mitsuba 3.9.1's own `hair` BSDF
(scalar_spectral), which tests/hair.rs holds spectrace's `Hair` to, and prints the sigmoid
coefficients Mitsuba's `srgb_model_fetch` gives the two pigments' RGB absorptions (the
constants `EUMELANIN_NM` and `PHEOMELANIN_NM` of src/material/hair.rs).

Each [[case]] gives the plugin's parameters and rows of: the direction towards the viewer
(Mitsuba's si.wi) and towards the light (its wo) in the fibre's local frame (+y along the fibre,
+z the normal), four wavelengths in nm, Mitsuba's eval (f·|cos θ_light|, its convention) at each,
and its pdf (sr⁻¹).

Usage: pip install mitsuba==3.9.1; python3 scripts/gen_hair_eval.py
"""
import math
import os
import random

import mitsuba as mi

mi.set_variant("scalar_spectral")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CASES = [
    ("default_brown", {}),
    ("blonde", {"eumelanin": 0.2, "pheomelanin": 0.4}),
    ("white_furnace", {"sigma_a": 0.0, "longitudinal_roughness": 0.5,
                       "azimuthal_roughness": 0.6, "scale_tilt": 0.0}),
    ("sigma_grey_smooth", {"sigma_a": 0.3, "longitudinal_roughness": 0.08,
                           "azimuthal_roughness": 0.1, "scale_tilt": 5.0}),
    # σₐ as a spectrum (λ:value pairs, 0 outside them as Mitsuba's `irregular`), not an RGB:
    # the two renderers' RGB upsampling tables differ at the spectrum's ends, which exp(−σₐ·l)
    # magnifies
    ("sigma_spectrum", {"sigma_a": [[400, 0.2], [500, 0.3], [600, 0.5], [700, 0.7]],
                        "scale": 2.0, "longitudinal_roughness": 0.25,
                        "azimuthal_roughness": 0.4}),
    ("rough_water", {"eumelanin": 0.5, "pheomelanin": 0.1, "longitudinal_roughness": 0.9,
                     "azimuthal_roughness": 0.95, "int_ior": 1.33, "scale_tilt": -3.0}),
]


def unit(rng, below=False):
    while True:
        v = [rng.uniform(-1, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        if 0.1 < n <= 1 and (v[2] < 0) == below:
            return [x / n for x in v]


def main():
    for name, rgb in (("EUMELANIN_NM", (0.419, 0.697, 1.37)),
                      ("PHEOMELANIN_NM", (0.187, 0.4, 1.05))):
        c = mi.srgb_model_fetch(mi.ScalarColor3f(*rgb))
        print(name, [repr(float(c[i])) for i in range(3)])
    out = ["# Written by scripts/gen_hair_eval.py with Mitsuba 3.9.1 scalar_spectral.", ""]
    rng = random.Random(2016)
    wavelengths = [[550, 430, 610, 480], [700, 400, 520, 650], [380, 590, 460, 800]]
    for name, params in CASES:
        d = {"type": "hair"}
        for k, v in params.items():
            if k == "sigma_a":
                d[k] = v if not isinstance(v, list) else {
                    "type": "irregular",
                    "wavelengths": ", ".join(str(p[0]) for p in v),
                    "values": ", ".join(str(p[1]) for p in v)}
            else:
                d[k] = v
        bsdf = mi.load_dict(d)
        ctx = mi.BSDFContext()
        rows = []
        for k in range(14):
            view = unit(rng, below=(k == 12))
            # lights around the specular cone and anywhere
            light = unit(rng, below=(k % 3 == 0))
            if k % 4 == 1:
                light = [-view[0] + 0.1 * rng.uniform(-1, 1), -view[1], -view[2]]
                n = math.sqrt(sum(x * x for x in light))
                light = [x / n for x in light]
            wl = wavelengths[k % 3]
            si = mi.SurfaceInteraction3f()
            si.p = [0, 0, 0]
            si.n = [0, 0, 1]
            si.sh_frame = mi.Frame3f(si.n)
            si.uv = [0.5, 0.5]
            si.wi = view
            si.wavelengths = wl
            wo = mi.Vector3f(light)
            value = bsdf.eval(ctx, si, wo)
            pdf = bsdf.pdf(ctx, si, wo)
            rows.append("  { view = [" + ", ".join(f"{x:.9g}" for x in view) + "], "
                        + "light = [" + ", ".join(f"{x:.9g}" for x in light) + "], "
                        + "lambda = [" + ", ".join(str(x) for x in wl) + "], "
                        + "value = [" + ", ".join(f"{float(value[i]):.9g}" for i in range(4))
                        + f"], pdf = {float(pdf):.9g} }},")
        def fmt(v):
            return "[" + ", ".join(str(x) for x in v) + "]" if isinstance(v, list) else str(v)
        out += ["[[case]]", f'name = "{name}"',
                "params = { " + ", ".join(f"{k} = {fmt(v)}" for k, v in params.items()) + " }",
                "rows = ["] + rows + ["]", ""]
    with open(os.path.join(ROOT, "tests", "data", "hair_eval.toml"), "w") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main()
