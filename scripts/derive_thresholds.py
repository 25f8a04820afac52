#!/usr/bin/env python3
"""Derive the idiff thresholds of every scene in tests/reference/ from measured noise.

For each scene: the Mitsuba noise is sigma_ref = RMS(ref_a - ref_b) / sqrt(2) (Y channel); the
spectrace noise is sigma_st = RMS(s1 - s2) / sqrt(2) for two spectrace renders with seeds 7 and 8
at the scene's spp (the harness renders with seed 7). The difference spectrace(seed 7) - ref_a has
sigma_d = sqrt(sigma_st^2 + sigma_ref^2). Thresholds, in Mitsuba-normalised Y units:
  fail = 5 sigma_d, warn = 3 sigma_d, failrelative = 0 (absolute test only),
  failpercent = twice the percentage of pixels where the two spectrace renders themselves differ
  by more than 5 sigma_d (the heavy tail of path-tracing noise: emitter edges, fireflies),
  at least 0.5 %.
A global bias of a few percent of the mean, which idiff's per-pixel test cannot see, is caught by
the closed-form tests (render_physics.rs) instead.

With --integrator bdpt the same is done for bidirectional path tracing, written to
thresholds_bdpt.toml, and the bdpt render (seed 7) is also compared with a path render (seed 7)
at the same spp: it prints their measured RMS difference against the one expected from both
noises, sqrt(sigma_bdpt^2 + sigma_path^2), with sigma_path from thresholds.toml.

Usage: cargo build --release && python3 scripts/derive_thresholds.py [--spp N] [--integrator I] [scene ...]
(the spp defaults to the scene's thresholds.toml, else 256)
Needs: pip install OpenImageIO numpy
"""
import argparse
import math
import os
import pathlib
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

ROOT = pathlib.Path(__file__).resolve().parent.parent
REF = ROOT / "tests" / "reference"
# the spectrace binary: $SPECTRACE_BIN, else target/release/spectrace (or under $CARGO_TARGET_DIR)
BIN = pathlib.Path(
    os.environ.get("SPECTRACE_BIN")
    or pathlib.Path(os.environ.get("CARGO_TARGET_DIR") or ROOT / "target") / "release" / "spectrace"
)


def channel(path, name):
    buf = oiio.ImageBuf(str(path))
    spec = buf.spec()
    idx = spec.channelindex(name)
    if idx < 0:
        sys.exit(f"{path}: no channel {name}")
    px = buf.get_pixels(oiio.FLOAT)
    return np.asarray(px)[:, :, idx].astype(np.float64)


def rms(a):
    return float(np.sqrt(np.mean(a * a)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=None)
    ap.add_argument("--integrator", default="path", choices=["path", "bdpt"])
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    out = ROOT / "target" / "thresholds"
    out.mkdir(parents=True, exist_ok=True)
    scenes = args.scenes or sorted(p.name for p in REF.iterdir() if (p / "scene.xml").is_file())
    for name in scenes:
        d = REF / name
        a, b = channel(d / "ref_a.exr", "Y"), channel(d / "ref_b.exr", "Y")
        sig_ref = rms(a - b) / math.sqrt(2)
        spp = args.spp or scene_spp(d)
        s = []
        for seed in (7, 8):
            s.append(render(d, out / f"{name}_{args.integrator}_{seed}", spp, seed, args.integrator))
        sig_st = rms(s[0] - s[1]) / math.sqrt(2)
        sig_d = math.sqrt(sig_st ** 2 + sig_ref ** 2)
        bias = float(np.mean(s[0]) / np.mean(a) - 1.0)
        tail = float(np.mean(np.abs(s[0] - s[1]) > 5 * sig_d)) * 100.0
        failpct = max(0.5, round(2 * tail, 2))
        measured = rms(s[0] - a)
        text = (
            f"# Derived by scripts/derive_thresholds.py from measured noise (Y, Mitsuba-normalised units).\n"
            f"# Mitsuba reference noise sigma_ref = RMS(ref_a - ref_b)/sqrt(2) = {sig_ref:.4g}\n"
            f"# integrator {args.integrator}\n"
            f"# spectrace noise at {spp} spp sigma_st = RMS(seed7 - seed8)/sqrt(2) = {sig_st:.4g}\n"
            f"# expected RMS of (spectrace - ref_a) = sqrt(sigma_st^2 + sigma_ref^2) = {sig_d:.4g}; measured {measured:.4g}\n"
            f"# mean Y spectrace / Mitsuba - 1 = {bias:+.4%}\n"
            f"spp = {spp}\n"
            f"fail = {5 * sig_d:.4g}\n"
            f"failrelative = 0.0\n"
            f"failpercent = {failpct}\n"
            f"warn = {3 * sig_d:.4g}\n"
            f'why = "fail at 5 sigma of the combined per-pixel noise (sigma_d = {sig_d:.3g}); at most {failpct} % of pixels, twice the tail of spectrace-vs-spectrace ({tail:.2f} %)"\n'
        )
        suffix = "" if args.integrator == "path" else f"_{args.integrator}"
        (d / f"thresholds{suffix}.toml").write_text(text)
        print(f"{name}: sigma_ref {sig_ref:.4g} sigma_st {sig_st:.4g} measured {measured:.4g} expected {sig_d:.4g} bias {bias:+.3%}")
        if args.integrator != "path":
            p = render(d, out / f"{name}_path_7", spp, 7, "path")
            sig_p = path_sigma(d)
            vs = rms(s[0] - p)
            want = math.sqrt(sig_st ** 2 + sig_p ** 2)
            pbias = float(np.mean(s[0]) / np.mean(p) - 1.0)
            print(f"  vs path: RMS {vs:.4g}, expected {want:.4g} (ratio {vs / want:.3f}); mean Y {pbias:+.3%}")


def scene_spp(d):
    t = d / "thresholds.toml"
    if t.is_file():
        for line in t.read_text().splitlines():
            if line.startswith("spp ="):
                return int(line.split("=")[1])
    return 256


def path_sigma(d):
    """sigma_st of `path` from the scene's thresholds.toml comment."""
    for line in (d / "thresholds.toml").read_text().splitlines():
        if "sigma_st = RMS" in line:
            return float(line.rsplit("=", 1)[1])
    sys.exit(f"{d}/thresholds.toml: no sigma_st")


def render(d, stem, spp, seed, integrator):
    exr = f"{stem}.exr"
    subprocess.run([str(BIN), "render", str(d / "scene.xml"), "--mitsuba-units", "--spp", str(spp),
                    "--integrator", integrator, "--seed", str(seed), "--quiet", "-o", exr,
                    "--png", f"{stem}.png"], check=True)
    return channel(exr, "Y")


if __name__ == "__main__":
    main()
