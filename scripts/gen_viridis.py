#!/usr/bin/env python3
"""Writes src/falsecolour/viridis.rs: the 256 entries of matplotlib's `viridis` colour map
(Nathaniel J. Smith and Stefan van der Walt, 2015; CC0 public domain), as 8-bit sRGB.
Run: pip install matplotlib==3.9.2; python3 scripts/gen_viridis.py
"""
import os

import matplotlib
import numpy as np

rgb = matplotlib.colormaps["viridis"].resampled(256)(np.arange(256))[:, :3]
out = os.path.join(os.path.dirname(__file__), "..", "src", "falsecolour", "viridis.rs")
with open(out, "w") as f:
    f.write("//! matplotlib's `viridis` colour map (Smith and van der Walt 2015, CC0), 256 entries of\n")
    f.write(f"//! 8-bit sRGB, written by scripts/gen_viridis.py from matplotlib {matplotlib.__version__}.\n\n")
    f.write("pub const VIRIDIS: [[u8; 3]; 256] = [\n")
    for r, g, b in rgb:
        f.write(f"    [{round(r * 255)}, {round(g * 255)}, {round(b * 255)}],\n")
    f.write("];\n")
