#!/usr/bin/env python3
"""Writes spectra/pbrt/media_presets.csv: the measured scattering coefficients pbrt-v4 names as
homogeneous-medium presets (`"string preset"`), read from its table in src/pbrt/media.cpp
(`SubsurfaceParameterTable`, a git mirror of mmp/pbrt-v4). The numbers are measurements:
Jensen, Marschner, Levoy & Hanrahan, "A Practical Model for Subsurface Light Transport",
SIGGRAPH 2001 (the first 12), and Narasimhan, Gupta, Donner, Ramamoorthi, Nayar & Jensen,
"Acquiring Scattering Properties of Participating Media by Dilution", SIGGRAPH 2006; reduced
scattering σ's and absorption σa in mm⁻¹ as RGB, which pbrt-v4 reads per unit of scene length.

Usage: python3 scripts/gen_pbrt_media_presets.py [/work/.mirror/mmp+pbrt-v4/repo]
"""
import os
import re
import subprocess
import sys

REPO = sys.argv[1] if len(sys.argv) > 1 else "/work/.mirror/mmp+pbrt-v4/repo"
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "spectra", "pbrt", "media_presets.csv")

src = subprocess.run(["git", "-C", REPO, "show", "HEAD:src/pbrt/media.cpp"],
                     check=True, capture_output=True, text=True).stdout
commit = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"],
                        check=True, capture_output=True, text=True).stdout.strip()
num = r"([-0-9.e]+)"
row = re.compile(r'\{"([^"]+)",\s*RGB\(' + r",\s*".join([num] * 3) + r"\),\s*RGB\("
                 + r",\s*".join([num] * 3) + r"\)\}")
rows = row.findall(src)
assert len(rows) >= 40, len(rows)
lines = [
    "# pbrt-v4's homogeneous-medium presets (src/pbrt/media.cpp, SubsurfaceParameterTable, "
    f"mmp/pbrt-v4 {commit}):",
    "# Jensen et al. 2001 (SIGGRAPH, 'A Practical Model for Subsurface Light Transport') and",
    "# Narasimhan et al. 2006 (SIGGRAPH, 'Acquiring Scattering Properties of Participating Media",
    "# by Dilution'). sigma_s is the reduced scattering coefficient, both in mm^-1 as RGB, read by",
    "# pbrt-v4 per unit of scene length. Written by scripts/gen_pbrt_media_presets.py.",
    "name,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b",
]
for name, *v in rows:
    lines.append(",".join([name] + v))
with open(OUT, "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"{OUT}: {len(rows)} presets")
