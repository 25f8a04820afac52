#!/usr/bin/env python3
"""Writes spectra/pbrt/<name>.csv: pbrt-v4's named glass and metal spectra (`glass-BK7`,
`metal-Au-eta`, …) as pbrt-v4 tabulates them in `src/pbrt/util/spectrum.cpp` (the arrays
`GlassBK7_eta`, `Au_eta`, … and the `namedSpectra` map), so that a pbrt-v4 scene naming them
is read with pbrt-v4's own numbers.

Usage: a bare git mirror of mmp/pbrt-v4 (the `fetch` tool: /work/.mirror/mmp+pbrt-v4/repo, or
set PBRT_REPO); python3 scripts/gen_pbrt_spectra.py
"""
import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPO = os.environ.get("PBRT_REPO", "/work/.mirror/mmp+pbrt-v4/repo")
COMMIT = "5f7a606806a4ac7b939131ded9d7a30ebd02416e"

# pbrt-v4's name → its array
NAMES = {f"glass-{g}": f"Glass{a}_eta" for g, a in
         [("BK7", "BK7"), ("BAF10", "BAF10"), ("FK51A", "FK51A"), ("LASF9", "LASF9"),
          ("F5", "SF5"), ("F10", "SF10"), ("F11", "SF11")]}
for m in ["Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"]:
    NAMES[f"metal-{m}-eta"] = f"{m}_eta"
    NAMES[f"metal-{m}-k"] = f"{m}_k"


def main():
    src = subprocess.run(["git", "-C", REPO, "show", f"{COMMIT}:src/pbrt/util/spectrum.cpp"],
                         check=True, capture_output=True, text=True).stdout
    out_dir = os.path.join(ROOT, "spectra", "pbrt")
    os.makedirs(out_dir, exist_ok=True)
    for name, array in NAMES.items():
        m = re.search(r"const Float " + re.escape(array) + r"\[\] = \{(.*?)\};", src, re.S)
        if not m:
            raise SystemExit(f"{array} not found")
        vals = [float(v) for v in m.group(1).replace("\n", " ").split(",") if v.strip()]
        assert len(vals) % 2 == 0, array
        rows = [(vals[i], vals[i + 1]) for i in range(0, len(vals), 2)]
        with open(os.path.join(out_dir, f"{name}.csv"), "w") as f:
            f.write(f"# pbrt-v4's named spectrum \"{name}\": the array {array} of "
                    f"src/pbrt/util/spectrum.cpp (mmp/pbrt-v4 {COMMIT[:8]}), as given.\n")
            f.write("# Written by scripts/gen_pbrt_spectra.py. pbrt-v4 extends a table with its end values\n"
                    "# to 359 and 831 nm when it does not reach them.\n")
            f.write("wavelength_nm,value\n")
            for l, v in rows:
                f.write(f"{l!r},{v!r}\n")
    print(len(NAMES), "files in", out_dir)


if __name__ == "__main__":
    main()
