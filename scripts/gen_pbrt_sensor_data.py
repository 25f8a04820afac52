#!/usr/bin/env python3
"""Writes the data pbrt-v4's `PixelSensor` (src/pbrt/film.h, film.cpp) uses, so that a pbrt-v4
film's `"string sensor"` is read with pbrt-v4's own numbers:

- spectra/pbrt/cameras/<name>.csv: the r, g, b sensitivities of pbrt-v4's named camera sensors
  (`canon_eos_5d_mkiv`, ...), the arrays `<name>_r`, `_g`, `_b` of src/pbrt/util/spectrum.cpp
  ("PhysLight code and measurements contributed by Anders Langlands and Luca Fascione,
  Copyright (c) 2020, Weta Digital, Ltd. SPDX-License-Identifier: Apache-2.0").
- spectra/pbrt/swatches_babelcolor.csv: the 24 ColorChecker reflectances pbrt-v4 fits a camera's
  XYZ matrix to (`PixelSensor::swatchReflectances`: Danny Pascale's BabelColor averages,
  380-730 nm at 10 nm), taken from colour-science's SDS_COLOURCHECKERS['BabelColor Average']
  and checked equal to pbrt-v4's table when the pbrt-v4 mirror is at hand.

Usage: pip install colour-science; a bare git mirror of mmp/pbrt-v4 (the `fetch` tool:
/work/.mirror/mmp+pbrt-v4/repo, or set PBRT_REPO); python3 scripts/gen_pbrt_sensor_data.py
"""
import os
import re
import subprocess

import colour

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPO = os.environ.get("PBRT_REPO", "/work/.mirror/mmp+pbrt-v4/repo")
COMMIT = "5f7a606806a4ac7b939131ded9d7a30ebd02416e"


def show(path):
    return subprocess.run(["git", "-C", REPO, "show", f"{COMMIT}:{path}"],
                          check=True, capture_output=True, text=True).stdout


def array(src, name):
    m = re.search(r"const Float " + re.escape(name) + r"\[\] = \{(.*?)\};", src, re.S)
    if not m:
        raise SystemExit(f"{name} not found")
    v = [float(x) for x in m.group(1).replace("\n", " ").split(",") if x.strip()]
    assert len(v) % 2 == 0, name
    return v[0::2], v[1::2]


def cameras():
    src = show("src/pbrt/util/spectrum.cpp")
    names = sorted(set(re.findall(r'\{"([a-z0-9_]+)_r",', src)))
    out_dir = os.path.join(ROOT, "spectra", "pbrt", "cameras")
    os.makedirs(out_dir, exist_ok=True)
    for name in names:
        (lr, r), (lg, g), (lb, b) = (array(src, f"{name}_{c}") for c in "rgb")
        assert lr == lg == lb, name
        with open(os.path.join(out_dir, f"{name}.csv"), "w") as f:
            f.write(f"# pbrt-v4's camera sensor \"{name}\": the arrays {name}_r, _g, _b of "
                    f"src/pbrt/util/spectrum.cpp (mmp/pbrt-v4 {COMMIT[:8]}), as given.\n"
                    "# Source: PhysLight measurements contributed by Anders Langlands and Luca Fascione,\n"
                    "# Copyright (c) 2020, Weta Digital, Ltd., Apache-2.0 (as stated in pbrt-v4's file).\n"
                    "# Written by scripts/gen_pbrt_sensor_data.py. pbrt-v4 extends each curve with its end\n"
                    "# values to 359 and 831 nm.\n")
            f.write("wavelength_nm,r,g,b\n")
            for row in zip(lr, r, g, b):
                f.write(",".join(repr(x) for x in row) + "\n")
    print(len(names), "cameras:", " ".join(names))
    return names


def swatches():
    cc = colour.SDS_COLOURCHECKERS["BabelColor Average"]
    names = list(cc.keys())
    lam = list(range(380, 731, 10))
    try:
        film = show("src/pbrt/film.cpp")
        tables = re.findall(r"FromInterleaved\(\s*\{(.*?)\}", film, re.S)[:24]
        for i, t in enumerate(tables):
            v = [float(x) for x in t.replace("\n", " ").split(",") if x.strip()]
            assert v[0::2] == [float(x) for x in lam], i
            assert max(abs(cc[names[i]][l] - y) for l, y in zip(lam, v[1::2])) < 1e-12, names[i]
        print("BabelColor averages equal pbrt-v4's swatchReflectances")
    except (subprocess.CalledProcessError, FileNotFoundError):
        print("pbrt-v4 mirror not found: swatches not compared")
    path = os.path.join(ROOT, "spectra", "pbrt", "swatches_babelcolor.csv")
    with open(path, "w") as f:
        f.write("# The 24 ColorChecker reflectances of pbrt-v4's PixelSensor::swatchReflectances\n"
                "# (src/pbrt/film.cpp): Danny Pascale's BabelColor averages (www.babelcolor.com),\n"
                "# 380-730 nm at 10 nm, from colour-science SDS_COLOURCHECKERS['BabelColor Average']\n"
                "# (BSD-3-Clause), equal to pbrt-v4's table. Written by scripts/gen_pbrt_sensor_data.py.\n")
        f.write("wavelength_nm," + ",".join(n.replace(" ", "_") for n in names) + "\n")
        for l in lam:
            f.write(f"{l}," + ",".join(repr(float(cc[n][l])) for n in names) + "\n")


if __name__ == "__main__":
    cameras()
    swatches()
