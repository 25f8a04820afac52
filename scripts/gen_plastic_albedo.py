#!/usr/bin/env python3
"""Directional albedo of Mitsuba 3.9.1's `plastic` and `roughplastic` with a white base
(diffuse_reflectance 0.5, so that `nonlinear` matters), estimated from Mitsuba's own BSDF sampler (mean of the sample weights,
which include the cosine), for tests/materials_energy.rs. Writes tests/data/plastic_albedo.csv.

Usage: pip install mitsuba==3.9.1; python3 scripts/gen_plastic_albedo.py
"""
import os

import numpy as np

import mitsuba as mi

mi.set_variant("scalar_spectral")
N = 100_000
RHO = 0.5
OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests", "data",
                   "plastic_albedo.csv")


def albedo(d, theta_deg):
    b = mi.load_dict(d)
    ctx = mi.BSDFContext()
    si = mi.SurfaceInteraction3f()
    t = np.radians(theta_deg)
    si.wi = mi.Vector3f(np.sin(t), 0, np.cos(t))
    rng = np.random.default_rng(int(theta_deg) + 7)
    w = np.empty(N)
    for k in range(N):
        _, wt = b.sample(ctx, si, float(rng.random()), mi.Point2f(float(rng.random()), float(rng.random())))
        w[k] = float(wt[0])
    return w.mean(), w.std() / np.sqrt(N)


rows = [f"# Mitsuba 3.9.1 scalar_spectral, diffuse_reflectance {RHO}, int_ior 1.49, ext_ior 1.000277;",
        f"# {N} samples of Mitsuba's own BSDF sampler per row (scripts/gen_plastic_albedo.py)",
        "kind,distribution,alpha,nonlinear,theta_deg,albedo,stderr"]
for kind, dist, alpha in [("plastic", "-", 0.0), ("roughplastic", "beckmann", 0.1),
                          ("roughplastic", "ggx", 0.4)]:
    for nonlinear in (False, True):
        for theta in (0.0, 45.0, 85.0):
            d = {"type": kind, "diffuse_reflectance": {"type": "spectrum", "value": RHO},
                 "nonlinear": nonlinear}
            if kind == "roughplastic":
                d.update({"distribution": dist, "alpha": alpha})
            m, e = albedo(d, theta)
            rows.append(f"{kind},{dist},{alpha},{str(nonlinear).lower()},{theta},{m:.6f},{e:.6f}")
            print(rows[-1], flush=True)
with open(OUT, "w") as f:
    f.write("\n".join(rows) + "\n")
print("wrote", OUT)
