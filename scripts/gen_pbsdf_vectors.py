#!/usr/bin/env python3
"""Test vectors for Mitsuba 3's `measured_polarized` BSDF (issue 28), evaluated by Mitsuba 3.9.1
`scalar_spectral_polarized` itself:

    pip install mitsuba==3.9.1 numpy && python3 scripts/gen_pbsdf_vectors.py

A synthetic pBSDF table with no symmetry (its values change with the sign of φ_d and between
light and view, non-reciprocal, and differ per wavelength and per Mueller element), made by
`table()` from polynomials of the grid coordinates (tests/measured_polarized.rs builds the same
table), is written as a `.pbsdf` tensor file; Mitsuba's `eval` (the Mueller matrix times
cos θ of the light direction, in its implicit bases of −ω_light and ω_view) and `pdf` are
recorded for direction pairs in radiance and importance transport into
tests/reference/pbsdf/vectors.txt, one line per query (and the table times 0.1 is written to
tests/reference/pbsdf/synthetic.pbsdf for the documentation scenes' references):

    mode wi_x wi_y wi_z wo_x wo_y wo_z lambda pdf m00 m01 ... m33

(`wi` is Mitsuba's si.wi, `wo` its eval argument; in radiance transport wo points to the light.)
No pair is an exact mirror configuration (h on the normal), where Mitsuba's φ_d is 0/0 and its
value NaN, then zero; M₀₀ stays positive over the table (Mitsuba clamps a negative M₀₀ to 0 and
keeps the other elements, which no physical matrix does).
"""
import os
import tempfile

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_spectral_polarized")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "reference", "pbsdf", "vectors.txt")
SCALED = os.path.join(ROOT, "tests", "reference", "pbsdf", "synthetic.pbsdf")

# the grids (radians, nm), as tests/measured_polarized.rs's `asym_grids`
PHI = np.linspace(-np.pi, np.pi, 9)
TD = np.linspace(0.0, np.pi / 2, 7)
TH = np.linspace(0.0, np.pi / 2, 8)
WVLS = np.array([450, 500, 550, 600, 650], dtype=np.uint16)


def table():
    """M[iφ, iθd, iθh, iλ, r, c]: element (r, c) = a polynomial in (φ_d, θ_d, θ_h, λ), computed
    in float64 and stored as float32 (tests/measured_polarized.rs's `asym_value`)."""
    m = np.zeros((len(PHI), len(TD), len(TH), len(WVLS), 4, 4), dtype=np.float64)
    for a, p in enumerate(PHI):
        for b, d in enumerate(TD):
            for c, h in enumerate(TH):
                for k, l in enumerate(WVLS):
                    x = (float(l) - 550.0) / 100.0
                    for r in range(4):
                        for s in range(4):
                            e = 4 * r + s
                            if e == 0:
                                v = 2.0 + 0.3 * p + 0.2 * d * d + 0.5 * h + 0.1 * x + 0.15 * p * d
                            else:
                                v = 0.02 * (e - 7.5) * (1.0 + 0.2 * p - 0.3 * d + 0.25 * h * h + 0.1 * x)
                            m[a, b, c, k, r, s] = v
    return m.astype(np.float32)


def write(path, scale=1.0):
    m = (table() * np.float32(scale)).astype(np.float32)
    fields = [("phi_d", 10, (1, len(PHI)), PHI.astype(np.float32)),
              ("theta_d", 10, (1, len(TD)), TD.astype(np.float32)),
              ("theta_h", 10, (1, len(TH)), TH.astype(np.float32)),
              ("wvls", 3, (len(WVLS),), WVLS),
              ("M", 10, m.shape, m)]
    head = b"tensor_file\0" + bytes([1, 0]) + len(fields).to_bytes(4, "little")
    hlen = len(head) + sum(2 + len(n) + 2 + 1 + 8 + 8 * len(s) for n, _, s, _ in fields)
    off = (hlen + 7) // 8 * 8
    data = b""
    for name, dt, shape, arr in fields:
        head += len(name).to_bytes(2, "little") + name.encode() + len(shape).to_bytes(2, "little")
        head += bytes([dt]) + off.to_bytes(8, "little")
        for d in shape:
            head += int(d).to_bytes(8, "little")
        b = np.ascontiguousarray(arr).tobytes()
        b += b"\0" * ((len(b) + 7) // 8 * 8 - len(b))
        off += len(b)
        data += b
    head += b"\0" * ((hlen + 7) // 8 * 8 - hlen)
    with open(path, "wb") as f:
        f.write(head + data)


def sph(theta, phi):
    t, p = np.radians(theta), np.radians(phi)
    return [float(np.sin(t) * np.cos(p)), float(np.sin(t) * np.sin(p)), float(np.cos(t))]


def main():
    path = os.path.join(tempfile.mkdtemp(), "asym.pbsdf")
    write(path)
    bsdf = mi.load_dict({"type": "measured_polarized", "filename": path, "alpha_sample": 0.2})
    pairs = [((10, 30), (35, 200)), ((40, 0), (38, 175)), ((60, 45), (20, 100)),
             ((25, -60), (55, 10)), ((70, 160), (65, 350)), ((5, 0), (50, 270)),
             ((45, 90), (30, 120)), ((80, 10), (15, 200))]
    lines = []
    for mode in ["radiance", "importance"]:
        ctx = mi.BSDFContext(mi.TransportMode.Radiance if mode == "radiance"
                             else mi.TransportMode.Importance)
        for (a, b) in pairs:
            for lam in [480.0, 575.0, 700.0]:
                si = mi.SurfaceInteraction3f()
                si.p = [0, 0, 0]
                si.n = [0, 0, 1]
                si.sh_frame = mi.Frame3f(si.n)
                si.wi = sph(*a)
                si.wavelengths = [lam] * 4
                wo = sph(*b)
                v = bsdf.eval(ctx, si, mi.Vector3f(wo))
                pdf = bsdf.pdf(ctx, si, mi.Vector3f(wo))
                m = [float(v[r, c][0]) for r in range(4) for c in range(4)]
                lines.append(" ".join([mode] + [f"{x:.9g}" for x in si.wi] + [f"{x:.9g}" for x in wo]
                                      + [f"{lam:g}", f"{float(pdf):.9g}"] + [f"{x:.9g}" for x in m]))
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        f.write("# generated by scripts/gen_pbsdf_vectors.py with Mitsuba " + mi.__version__ + "\n")
        f.write("\n".join(lines) + "\n")
    print(f"{len(lines)} vectors -> {OUT}")
    # the same table times 0.1 (an albedo below 1), which tests/polarised_reference.rs and
    # scripts/gen_polarised_refs.py put in Mitsuba's measured_polarized documentation scenes
    # in place of the KAIST gold data that mitsuba-data does not distribute
    write(SCALED, 0.1)
    print(f"-> {SCALED}")


if __name__ == "__main__":
    main()
