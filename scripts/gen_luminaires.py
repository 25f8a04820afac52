#!/usr/bin/env python3
"""Writes the synthetic luminaire files in scenes/luminaires/ from closed forms (not measured
data; written for the example scenes):

- downlight.ies (IES LM-63-2002, type C, one plane): I(γ) = 1000 cd · cos^1.5 γ below the
  horizon, 0 above; absolute photometry (lumens per lamp −1). Its flux is
  2π · 1000 / 2.5 = 2513.3 lm up to the table's 2.5° steps.
- linear.ldt (EULUMDAT, Isym 4, 24 C-planes of 15°): a linear luminaire,
  I(γ, C) = cos γ · (0.6 + 0.4 · cos² C) in cd/klm · 300 below the horizon, for one 4000 lm
  lamp set.

Run: python3 scripts/gen_luminaires.py
"""
import math
import os

OUT = os.path.join(os.path.dirname(__file__), "..", "scenes", "luminaires")


def downlight():
    v = [2.5 * k for k in range(73)]  # 0–180°
    cd = [1000.0 * math.cos(math.radians(g)) ** 1.5 if g < 90 else 0.0 for g in v]
    lines = [
        "IESNA:LM-63-2002",
        "[TEST] synthetic: I = 1000 cd cos^1.5(gamma), scripts/gen_luminaires.py",
        "[MANUFAC] spectrace example",
        "[LUMCAT] downlight",
        "[LUMINAIRE] recessed downlight, closed form",
        "TILT=NONE",
        f"1 -1 1 {len(v)} 1 1 2 0.15 0.15 0",
        "1 1 20",
    ]
    for k in range(0, len(v), 10):
        lines.append(" ".join(f"{x:g}" for x in v[k:k + 10]))
    lines.append("0")
    for k in range(0, len(cd), 8):
        lines.append(" ".join(f"{x:.4f}" for x in cd[k:k + 8]))
    return "\r\n".join(lines) + "\r\n"


def linear():
    mc, dc, g = 24, 15.0, [5.0 * k for k in range(37)]
    flux = 4000.0
    out = ["spectrace example (synthetic, scripts/gen_luminaires.py)", "2", "4", str(mc), "15", str(len(g)), "5",
           "synthetic", "linear luminaire, closed form", "L-1", "linear.ldt", "2026-11-29",
           "1200", "150", "60", "1150", "100", "0", "0", "0", "0", "100"]
    # LOR: the closed form's flux over the lamp flux (computed below by quadrature)
    def i(gam, c):
        return 300.0 * max(math.cos(math.radians(gam)), 0.0) * (0.6 + 0.4 * math.cos(math.radians(c)) ** 2)
    n = 720
    phi = 0.0
    for a in range(n):
        gam = (a + 0.5) * 180.0 / n
        for b in range(n):
            c = (b + 0.5) * 360.0 / n
            phi += i(gam, c) * math.sin(math.radians(gam)) * math.radians(180.0 / n) * math.radians(360.0 / n)
    lor = phi * flux / 1000.0 / flux * 100.0
    out += [f"{lor:.3f}", "1", "0", "1", "1", "LED 840", f"{flux:g}", "4000K", "1B", "35"]
    out += ["0.5"] * 10
    out += [f"{k * dc:g}" for k in range(mc)]
    out += [f"{x:g}" for x in g]
    for c in [k * dc for k in range(mc // 4 + 1)]:
        out += [f"{i(x, c):.4f}" for x in g]
    return "\r\n".join(out) + "\r\n"


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "downlight.ies"), "w", newline="") as f:
        f.write(downlight())
    with open(os.path.join(OUT, "linear.ldt"), "w", newline="") as f:
        f.write(linear())
