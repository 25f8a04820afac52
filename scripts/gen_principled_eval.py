#!/usr/bin/env python3
"""Writes tests/data/principled_eval.toml: values and densities of Mitsuba 3.9.1's own
`principled` and `principledthin` BSDFs (scalar_spectral), which tests/principled.rs holds
spectrace's `Principled` to.

Each [[case]] gives the plugin's parameters (numbers only, the base colour a flat spectrum so that
no RGB uplifting enters) and rows of: the direction towards the viewer (Mitsuba's si.wi), the
direction towards the light (Mitsuba's wo), both in the local frame, four wavelengths in nm,
Mitsuba's eval (f·|cos θ_light|) at each wavelength in radiance mode, and its pdf (sr⁻¹).

Usage: pip install mitsuba==3.9.1; python3 scripts/gen_principled_eval.py
"""
import math
import os

import mitsuba as mi

mi.set_variant("scalar_spectral")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CASES = [
    ("principled", "diffuse_only", {"base_color": 0.6, "roughness": 0.4, "specular": 0.0}),
    ("principled", "plastic_like", {"base_color": 0.3, "roughness": 0.35, "specular": 0.5}),
    ("principled", "metal", {"base_color": 0.8, "roughness": 0.3, "metallic": 1.0}),
    ("principled", "everything", {"base_color": 0.5, "roughness": 0.45, "metallic": 0.3,
                                  "spec_tint": 0.6, "anisotropic": 0.5, "sheen": 0.7,
                                  "sheen_tint": 0.4, "clearcoat": 0.8, "clearcoat_gloss": 0.3,
                                  "spec_trans": 0.4, "flatness": 0.5, "eta": 1.45}),
    ("principled", "glass", {"base_color": 0.9, "roughness": 0.25, "spec_trans": 1.0,
                             "eta": 1.5}),
    ("principledthin", "thin_everything", {"base_color": 0.7, "roughness": 0.4, "spec_trans": 0.5,
                                           "diff_trans": 0.8, "sheen": 0.5, "sheen_tint": 0.3,
                                           "spec_tint": 0.4, "flatness": 0.3, "anisotropic": 0.3,
                                           "eta": 1.33}),
    ("principledthin", "thin_diffuse", {"base_color": 0.5, "roughness": 0.6, "diff_trans": 1.2}),
]


def direction(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]


# (viewer, light) pairs: reflection, transmission, grazing, from below
PAIRS = [((20, 0), (35, 180)), ((50, 30), (40, 200)), ((10, 90), (60, 250)),
         ((70, 10), (75, 190)), ((30, 0), (150, 170)), ((45, 60), (130, 260)),
         ((160, 0), (145, 180)), ((140, 40), (30, 220)), ((0.5, 0), (5, 180)),
         ((60, 0), (60, 180))]
WAVELENGTHS = [[550, 430, 610, 480], [700, 400, 520, 650]]


def main():
    out = ["# Written by scripts/gen_principled_eval.py with Mitsuba 3.9.1 scalar_spectral.", ""]
    for plugin, name, params in CASES:
        props = "".join(f'<float name="{k}" value="{v}"/>' for k, v in params.items())
        bsdf = mi.load_string(f'<bsdf version="3.0.0" type="{plugin}">{props}</bsdf>')
        ctx = mi.BSDFContext()
        rows = []
        for k, (v, l) in enumerate(PAIRS):
            wl = WAVELENGTHS[k % 2]
            si = mi.SurfaceInteraction3f()
            si.p = [0, 0, 0]
            si.n = [0, 0, 1]
            si.sh_frame = mi.Frame3f(si.n)
            si.uv = [0.5, 0.5]
            si.wi = direction(*v)
            si.wavelengths = wl
            wo = mi.Vector3f(direction(*l))
            value = bsdf.eval(ctx, si, wo)
            pdf = bsdf.pdf(ctx, si, wo)
            rows.append("  { view = [" + ", ".join(f"{x:.9g}" for x in direction(*v)) + "], "
                        + "light = [" + ", ".join(f"{x:.9g}" for x in direction(*l)) + "], "
                        + "lambda = [" + ", ".join(str(x) for x in wl) + "], "
                        + "value = [" + ", ".join(f"{float(value[i]):.9g}" for i in range(4))
                        + f"], pdf = {float(pdf):.9g} }},")
        out += ["[[case]]", f'plugin = "{plugin}"', f'name = "{name}"',
                "params = { " + ", ".join(f"{k} = {v}" for k, v in params.items()) + " }",
                "rows = ["] + rows + ["]", ""]
    with open(os.path.join(ROOT, "tests", "data", "principled_eval.toml"), "w") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main()
