#!/usr/bin/env python3
"""CIE standard general sky (CIE S 011/E:2003 = ISO 15469:2004) test vectors.

  L(Z, alpha) / L_z = f(chi) phi(Z) / ( f(Z_s) phi(0) )
  phi(Z) = 1 + a exp(b / cos Z)            (phi(pi/2) = 1 for b < 0)
  f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi
  cos chi = cos Z_s cos Z + sin Z_s sin Z cos(alpha - alpha_s)

Outputs tests/data/cie_sky_vectors.csv with
  kind=Eh        : E_h / L_z  (horizontal illuminance from the whole unobstructed sky / zenith
                   luminance, sun excluded) computed two independent ways (adaptive scipy
                   quadrature and a split Gauss-Legendre product rule), and their difference.
  kind=L         : point values L/L_z for a few directions (for unit-testing the distribution).
  kind=MoonSpencer / DF_* : overcast checks and the roof-light daylight factors.
"""
import math
import csv
import numpy as np
from scipy import integrate

# Type: (a, b, c, d, e)   -- CIE S 011/E:2003 Table 1 (gradation groups I-VI, indicatrix groups 1-6)
CIE_TYPES = {
    1: (4.0, -0.70, 0.0, -1.0, 0.00),
    2: (4.0, -0.70, 2.0, -1.5, 0.15),
    3: (1.1, -0.80, 0.0, -1.0, 0.00),
    4: (1.1, -0.80, 2.0, -1.5, 0.15),
    5: (0.0, -1.00, 0.0, -1.0, 0.00),
    6: (0.0, -1.00, 2.0, -1.5, 0.15),
    7: (0.0, -1.00, 5.0, -2.5, 0.30),
    8: (0.0, -1.00, 10.0, -3.0, 0.45),
    9: (-1.0, -0.55, 2.0, -1.5, 0.15),
    10: (-1.0, -0.55, 5.0, -2.5, 0.30),
    11: (-1.0, -0.55, 10.0, -3.0, 0.45),
    12: (-1.0, -0.32, 10.0, -3.0, 0.45),
    13: (-1.0, -0.32, 16.0, -3.0, 0.30),
    14: (-1.0, -0.15, 16.0, -3.0, 0.30),
    15: (-1.0, -0.15, 24.0, -2.8, 0.15),
}


def phi(Z, a, b):
    cz = np.cos(Z)
    with np.errstate(divide="ignore", over="ignore"):
        ex = np.where(cz > 1e-12, np.exp(b / np.maximum(cz, 1e-300)), 0.0)
    return 1.0 + a * ex


def f_ind(chi, c, d, e):
    return 1.0 + c * (np.exp(d * chi) - math.exp(d * math.pi / 2)) + e * np.cos(chi) ** 2


def rel_lum(Z, dalpha, Zs, t):
    """L/L_z at zenith angle Z, azimuth difference dalpha (alpha - alpha_s), sun zenith Zs."""
    a, b, c, d, e = CIE_TYPES[t]
    cchi = np.clip(np.cos(Zs) * np.cos(Z) + np.sin(Zs) * np.sin(Z) * np.cos(dalpha), -1.0, 1.0)
    chi = np.arccos(cchi)
    return f_ind(chi, c, d, e) * phi(Z, a, b) / (f_ind(Zs, c, d, e) * phi(0.0, a, b))


def eh_scipy(t, Zs):
    # symmetric about the sun's vertical: integrate dalpha in [0, pi] and double.
    # inner Z integral split at Zs (kink of chi at the sun).
    def inner(da):
        g = lambda Z: rel_lum(Z, da, Zs, t) * math.cos(Z) * math.sin(Z)
        r1 = integrate.quad(g, 0.0, Zs, epsabs=1e-14, epsrel=1e-13, limit=400)[0]
        r2 = integrate.quad(g, Zs, math.pi / 2, epsabs=1e-14, epsrel=1e-13, limit=400)[0]
        return r1 + r2
    v = integrate.quad(inner, 0.0, math.pi, epsabs=1e-13, epsrel=1e-12, limit=400)[0]
    return 2.0 * v


def eh_gauss(t, Zs, n=400):
    # Product Gauss-Legendre; Z split at Zs, dalpha graded towards 0 (the sun's vertical)
    # through the substitution dalpha = pi * s^3 (s in [0,1]) to resolve the circumsolar peak.
    xg, wg = np.polynomial.legendre.leggauss(n)
    def nodes(lo, hi):
        return 0.5 * (hi - lo) * xg + 0.5 * (hi + lo), 0.5 * (hi - lo) * wg
    Z1, w1 = nodes(0.0, Zs)
    Z2, w2 = nodes(Zs, math.pi / 2)
    Z = np.concatenate([Z1, Z2]); wZ = np.concatenate([w1, w2])
    s, ws = nodes(0.0, 1.0)
    da = math.pi * s ** 3
    wda = ws * 3.0 * math.pi * s ** 2
    ZZ, DA = np.meshgrid(Z, da, indexing="ij")
    val = rel_lum(ZZ, DA, Zs, t) * np.cos(ZZ) * np.sin(ZZ)
    return 2.0 * float(wZ @ val @ wda)


def main():
    rows = []
    for t in (1, 5, 12):
        for elev in (30.0, 60.0):
            Zs = math.radians(90.0 - elev)
            v1 = eh_scipy(t, Zs)
            v2 = eh_gauss(t, Zs)
            rows.append(dict(kind="Eh", sky_type=t, sun_elev_deg=elev, Z_deg="", dalpha_deg="",
                             value=f"{v1:.10f}", check=f"{v2:.10f}", note=f"diff {v1 - v2:.1e}"))
    # point values of L/L_z
    for t in (1, 5, 12):
        for elev in (30.0, 60.0):
            Zs = math.radians(90.0 - elev)
            for Zd, dad in [(0, 0), (45, 0), (45, 90), (45, 180), (80, 0), (80, 180),
                            (90.0 - elev, 10.0), (89.9, 0)]:
                v = float(rel_lum(math.radians(Zd), math.radians(dad), Zs, t))
                rows.append(dict(kind="L", sky_type=t, sun_elev_deg=elev, Z_deg=Zd, dalpha_deg=dad,
                                 value=f"{v:.10f}", check="", note="L/L_z"))
    # Moon-Spencer overcast: E_h/L_z = 7 pi / 9 ; and type 1 vs MS comparison
    ms = 2 * math.pi * integrate.quad(lambda Z: (1 + 2 * math.cos(Z)) / 3 * math.cos(Z) * math.sin(Z),
                                      0, math.pi / 2, epsabs=1e-15)[0]
    rows.append(dict(kind="MoonSpencer", sky_type="", sun_elev_deg="", Z_deg="", dalpha_deg="",
                     value=f"{ms:.12f}", check=f"{7 * math.pi / 9:.12f}", note="Eh/Lz numeric vs 7pi/9"))
    Zg = np.linspace(0, math.pi / 2, 100001)
    d = rel_lum(Zg, 0.0, 0.3, 1) - (1 + 2 * np.cos(Zg)) / 3
    i = int(np.argmax(np.abs(d)))
    rows.append(dict(kind="Type1_minus_MS_max", sky_type=1, sun_elev_deg="", Z_deg=f"{math.degrees(Zg[i]):.3f}",
                     dalpha_deg="", value=f"{d[i]:.6f}", check="", note="max |L1/Lz - (1+2cosZ)/3|"))

    # Roof-light daylight factor (sky component only), point on the floor below the centre
    def rect_PQ(a, b, h):
        def corner(A, B):
            X, Y = A / h, B / h
            P = 0.5 * (X / math.hypot(1, X) * math.atan(Y / math.hypot(1, X))
                       + Y / math.hypot(1, Y) * math.atan(X / math.hypot(1, Y)))
            D = math.sqrt(A * A + B * B + h * h)
            Q = (math.atan(A * B / (h * D)) + A * B * h / D * (1 / (A * A + h * h) + 1 / (B * B + h * h))) / 3
            return P, Q
        P, Q = corner(a / 2, b / 2)
        return 4 * P, 4 * Q

    def rect_numeric(a, b, h, ms=True):
        w = (lambda r: (1 + 2 * h / r) / 3) if ms else (lambda r: 1.0)
        g = lambda y, x: w(math.sqrt(x * x + y * y + h * h)) * h * h / (x * x + y * y + h * h) ** 2
        v = integrate.dblquad(g, -a / 2, a / 2, -b / 2, b / 2, epsabs=1e-14, epsrel=1e-12)[0]
        return v / ((7 * math.pi / 9) if ms else math.pi)

    for (a, b, h) in [(1.0, 1.0, 3.0), (2.0, 1.0, 2.5), (4.0, 4.0, 1.0)]:
        P, Q = rect_PQ(a, b, h)
        df_ms = 3 * (P + 2 * Q) / (7 * math.pi)
        df_u = P / math.pi
        rows.append(dict(kind="DF_rect_MoonSpencer", sky_type="", sun_elev_deg="", Z_deg="", dalpha_deg="",
                         value=f"{df_ms:.10f}", check=f"{rect_numeric(a, b, h):.10f}",
                         note=f"hole {a}x{b} m at h={h} m; value=closed form, check=dblquad"))
        rows.append(dict(kind="DF_rect_uniform", sky_type="", sun_elev_deg="", Z_deg="", dalpha_deg="",
                         value=f"{df_u:.10f}", check=f"{rect_numeric(a, b, h, ms=False):.10f}",
                         note=f"hole {a}x{b} m at h={h} m (uniform sky = view factor)"))
    for (R, h) in [(0.5, 3.0), (0.5641895835, 3.0), (1.0, 1.0)]:
        c0 = h / math.hypot(R, h); s2 = R * R / (R * R + h * h)
        df_ms = (3 * s2 + 4 * (1 - c0 ** 3)) / 7
        num = 2 * math.pi * integrate.quad(lambda Z: (1 + 2 * math.cos(Z)) / 3 * math.cos(Z) * math.sin(Z),
                                           0, math.atan2(R, h), epsabs=1e-15)[0] / (7 * math.pi / 9)
        rows.append(dict(kind="DF_disk_MoonSpencer", sky_type="", sun_elev_deg="", Z_deg="", dalpha_deg="",
                         value=f"{df_ms:.10f}", check=f"{num:.10f}", note=f"disk R={R} m at h={h} m"))
        rows.append(dict(kind="DF_disk_uniform", sky_type="", sun_elev_deg="", Z_deg="", dalpha_deg="",
                         value=f"{s2:.10f}", check="", note=f"disk R={R} m at h={h} m: R^2/(R^2+h^2)"))

    with open(__import__("os").path.join(__import__("os").path.dirname(__file__), "..", "tests", "data", "cie_sky_vectors.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=["kind", "sky_type", "sun_elev_deg", "Z_deg", "dalpha_deg",
                                           "value", "check", "note"])
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        print(r)


if __name__ == "__main__":
    main()
