#!/usr/bin/env python3
"""Colour noise of the default scene (scenes/prism.toml): per-pixel chromaticity variance and the
rainbow's hue steps, for several render configurations at equal time.

How to run (from the repository root; needs numpy and OpenImageIO):

    python3 scripts/bench_colour_noise.py    # configs hero=--dispersion hero and split= (defaults)
    python3 scripts/bench_colour_noise.py --spp 2 --seeds 2 --config a= --config "b=--threads 1"

--config NAME=EXTRA_ARGS (repeatable): extra `spectrace render` arguments, empty = the scene's
defaults. --common-args="ARGS" are appended to every config's (e.g. "--exposure 7"). --seeds N
(seeds 1..N, default 4), --spp N (default: the scene's), --json FILE, --keep DIR (keep the
renders), --overlay FILE (the first config's mean PNG, prism mask cyan, rainbow run yellow).

Equal time (default): the FIRST config renders at --spp (or the scene's spp); its mean wall time
per render, measured around the subprocess, is the budget. Every other config first renders
seed 1 at that spp to measure its own time, and then renders all seeds at the spp that fits the
budget (rounded). --equal-spp renders every config at the same spp instead. Samples per pixel
come from the EXR attribute spectrace:samplesPerPixel.

  * Chromaticity variance: x = X/(X+Y+Z), y = Y/(X+Y+Z) per pixel and seed (EXR channels X, Y,
    Z); over the seeds, var(x) + var(y) (ddof = 1), averaged over the pixels with X+Y+Z > 0 in
    every seed, in the prism region and over the whole image. Ratios: first config ÷ each other.
  * Prism region: every `mesh` shape with a `dielectric` material, its vertices projected through
    the scene's pinhole camera (`fov` spans `fov_axis`, default x = horizontal, as the loader;
    pixel row 0 at the top), the 2D convex hull of the projections rasterised (pixel centres).
  * Rainbow: where the scene's `[[lights]]` alone (the beam; emitting shapes removed from the
    TOML, rendered by `light` at 16 spp) light the image outside the prism: the row with the
    most of that light, and in it the longest run of pixels over --frac 0.05 of the row's
    peak (gaps of 1 px allowed). In the 8-bit sRGB PNG (the display transform's output), the
    rows within --band 4 of the run's averaged (the spectrum is the same along its height),
    over the run's pixels with HSV saturation > --sat 0.3 (where the spectrum is dim over the
    lit wall its pixels are nearly grey and their hue is noise): the hue range (unwrapped,
    deg), the largest hue step between neighbouring coloured pixels, the steps > 15 deg; and
    the run's pixels with two or more channels at 0 or 255 (clipped). In the mean of the
    seeds' PNGs, and "per seed max": the same on each seed's PNG, the maximum over the seeds.
    The PNGs' exposure is automatic (per image, from the geometric mean luminance).
"""

from __future__ import annotations

import argparse
import itertools
import json
import re
import math
import shlex
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_common import cpu_model, loadavg, read_exr  # noqa: E402
from bench_efficiency import git_head, log  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_CONFIGS = ["hero=--dispersion hero", "split="]
SAT, FRAC, STEP, BAND = 0.3, 0.05, 15.0, 4


def angle_rad(s: str) -> float:
    """"50 deg", "50°" or "0.87 rad" (the scene's angle strings)."""
    v, _, unit = s.replace("°", " deg").partition(" ")
    return math.radians(float(v)) if unit.strip() in ("deg", "degree", "degrees") else float(v)


def prism_mask(scene: dict, w: int, h: int) -> np.ndarray:
    """Pixels (centres) inside the projected convex hull of each dielectric mesh, row 0 at top."""
    cam = scene["camera"]
    if cam.get("type", "perspective") not in ("perspective", "thinlens") or "fov" not in cam:
        raise SystemExit("the prism mask needs a perspective camera with `fov`")
    eye, target = np.array(cam["eye"], float), np.array(cam["target"], float)
    d = (target - eye) / np.linalg.norm(target - eye)
    left = np.cross(np.array(cam.get("up", [0.0, 1.0, 0.0]), float), d)  # Transform::look_at
    left /= np.linalg.norm(left)
    up = np.cross(d, left)
    t = math.tan(angle_rad(cam["fov"]) / 2)
    horiz = {"x": True, "y": False, "larger": w >= h, "smaller": w <= h}[cam.get("fov_axis", "x")]
    hx, hy = (t, t * h / w) if horiz else (t * w / h, t)
    mats, mask = scene.get("materials", {}), np.zeros((h, w), bool)
    yy, xx = np.mgrid[0:h, 0:w] + 0.5
    for sh in scene.get("shapes", []):
        m = sh.get("material")
        m = mats.get(m, {}) if isinstance(m, str) else (m or {})
        if sh.get("type") != "mesh" or m.get("type") != "dielectric":
            continue
        if "transform" in sh or "vertices" not in sh:
            raise SystemExit("dielectric mesh with a transform or no inline vertices: unsupported")
        p = np.array(sh["vertices"], float) - eye
        z = p @ d
        if np.any(z <= 0):
            raise SystemExit("a dielectric mesh vertex is behind the camera")
        # camera plane -> raster as geometry::camera::Film::raster: ndc = -xy / half
        q = np.stack([(1 - (p @ left) / z / hx) / 2 * w, (1 - (p @ up) / z / hy) / 2 * h], 1)
        # the convex hull of points is the union of the triangles they make (Carathéodory)
        for a, b, c in itertools.combinations(q, 3):
            e = [(v1[0] - v0[0]) * (yy - v0[1]) - (v1[1] - v0[1]) * (xx - v0[0])
                 for v0, v1 in ((a, b), (b, c), (c, a))]
            mask |= ((e[0] >= 0) & (e[1] >= 0) & (e[2] >= 0))
            mask |= ((e[0] <= 0) & (e[1] <= 0) & (e[2] <= 0))
    return mask


def write_png(path: Path, rgb: np.ndarray) -> None:
    out = oiio.ImageOutput.create(str(path))
    out.open(str(path), oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, "uint8"))
    out.write_image(np.ascontiguousarray(np.clip(rgb, 0, 255).astype(np.uint8)))
    out.close()


def hsv(rgb: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Hue (deg), saturation and value of 8-bit-scaled RGB."""
    c = rgb / 255.0
    mx, mn = c.max(-1), c.min(-1)
    dl = np.where(mx > mn, mx - mn, 1.0)
    r, g, b = c[..., 0], c[..., 1], c[..., 2]
    hue = np.where(mx == r, (g - b) / dl % 6, np.where(mx == g, (b - r) / dl + 2, (r - g) / dl + 4))
    return 60.0 * hue, np.where(mx > 0, (mx - mn) / np.where(mx > 0, mx, 1), 0.0), mx


def beam_only(binary: str, scene_path: Path, outdir: Path) -> np.ndarray:
    """Luminance of the scene lit by its `[[lights]]` alone (every emitting shape removed from
    the TOML text), by light tracing at 16 spp: where the beam's light lands."""
    blocks = re.split(r"(?m)^(?=\[)", scene_path.read_text())
    kept = [b for b in blocks if not (b.startswith("[[shapes]]") and "emission" in b)]
    path = outdir / "beam_only.toml"
    path.write_text("".join(kept))
    out = outdir / "beam_only.exr"
    render(binary, path, out, 0, ["--integrator", "light", "--spp", "16"])
    return read_exr(out)[0]["Y"]


def rainbow_run(beam_y: np.ndarray, mask: np.ndarray, frac: float) -> tuple[int, np.ndarray]:
    """The rainbow's row (the most beam light outside the prism) and its pixels there: the
    longest run (gaps of 1 px allowed) of pixels over `frac` of the row's brightest."""
    y = np.where(mask, 0.0, beam_y)
    row = int(np.argmax(y.sum(1)))
    idx = np.flatnonzero(y[row] > frac * y[row].max())
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 2) + 1)
    return row, max(runs, key=lambda r: r[-1] - r[0])


def rainbow(rgb: np.ndarray, row: int, run: np.ndarray, smin: float = SAT, band: int = BAND) -> dict:
    """Hue steps along `run` of `row` in the PNG, the rows within `band` of it averaged (the
    spectrum is the same along its height; the average lowers the noise's part in the hue),
    over the pixels with HSV saturation above `smin` (the hue of a near-grey pixel is noise)."""
    rgb = rgb.copy()
    rgb[row] = rgb[max(row - band, 0) : row + band + 1].mean(0)
    hue, s, _ = hsv(rgb)
    span = np.arange(run[0], run[-1] + 1)
    coloured = span[s[row, span] > smin]
    hu = np.unwrap(hue[row, coloured], period=360.0) if len(coloured) else np.zeros(1)
    # steps between neighbouring pixels that are both coloured (a gap is not a step)
    steps = np.abs(np.diff(hu))[np.diff(coloured) == 1] if len(coloured) > 1 else np.zeros(0)
    px = rgb[row, run[0] : run[-1] + 1]
    clipped = ((px == 0) | (px == 255)).sum(-1) >= 2
    return {"row": row, "start": int(run[0]), "length": int(run[-1] - run[0] + 1),
            "coloured": int(len(coloured)), "hue_range": float(hu.max() - hu.min()),
            "max_step": float(steps.max()) if len(steps) else 0.0,
            "steps_over_15": int((steps > STEP).sum()), "clipped2": int(clipped.sum())}


def chroma_var(xyz: list[np.ndarray], mask: np.ndarray) -> tuple[float, float, int]:
    a = np.stack(xyz)  # seeds × 3 × h × w
    s = a.sum(1)
    ok = np.all(s > 0, 0)
    s = np.where(s > 0, s, 1.0)
    v = np.var(a[:, 0] / s, 0, ddof=1) + np.var(a[:, 1] / s, 0, ddof=1)
    return float(v[ok & mask].mean()), float(v[ok].mean()), int(ok.sum())


def render(binary: str, scene: Path, out: Path, seed: int, args: list[str]) -> float:
    cmd = [binary, "render", str(scene), "-o", str(out), "--png", str(out.with_suffix(".png")),
           "--seed", str(seed), "--quiet", *args]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    t = time.perf_counter() - t0
    if r.returncode != 0:
        raise SystemExit(f"`{shlex.join(cmd)}` failed ({r.returncode}):\n{r.stderr[-2000:]}")
    return t


def measure(a, name: str, args: list[str], outdir: Path, mask: np.ndarray, rb_at) -> dict:
    """Renders one config for every seed and returns its figures."""
    walls, xyz, pngs, spps, rts = [], [], [], [], []
    for s in range(1, a.seeds + 1):
        out = outdir / f"{name}_s{s}.exr"
        log(f"{name} seed {s}: {shlex.join(args)}")
        walls.append(render(a.binary, a.scene, out, s, args))
        ch, attrs = read_exr(out)
        xyz.append(np.stack([ch["X"], ch["Y"], ch["Z"]]))
        png, _ = read_exr(out.with_suffix(".png"))  # OpenImageIO reads any format
        pngs.append(np.rint(np.stack([png[c] for c in "RGB"], -1) * 255.0))
        spps.append(attrs.get("spectrace:samplesPerPixel"))
        rts.append(attrs.get("spectrace:renderTimeSeconds"))
    vp, vi, nok = chroma_var(xyz, mask)
    mean_png = np.mean(pngs, 0)
    rb = rainbow(mean_png, *rb_at, a.sat, a.band)
    per_seed = [rainbow(p, *rb_at, a.sat, a.band) for p in pngs]
    return {"args": args, "wall_s": float(np.mean(walls)), "walls": walls, "spp": spps,
            "render_s": None if None in rts else float(np.mean(rts)),
            "chroma_var_prism": vp, "chroma_var_image": vi, "valid_px": nok,
            "rainbow_mean": rb, "rainbow_per_seed": per_seed,
            "rainbow_seed_max": {k: "/".join(str(r[k]) for r in per_seed) if k == "row"
                                 else max(r[k] for r in per_seed) for k in per_seed[0]},
            "mean_png": mean_png}


def main() -> int:
    ap = argparse.ArgumentParser(description=" ".join(__doc__.split("\n")[:2]))
    ap.add_argument("--config", action="append", metavar="NAME=EXTRA_ARGS")
    ap.add_argument("--scene", type=Path, default=ROOT / "scenes" / "prism.toml")
    ap.add_argument("--binary", default=str(ROOT / "target" / "release" / "spectrace"))
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--spp", type=int, default=None)
    ap.add_argument("--equal-spp", action="store_true")
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument("--keep", type=Path, default=None)
    ap.add_argument("--overlay", type=Path, default=None)
    ap.add_argument("--sat", type=float, default=SAT, help="rainbow: HSV saturation above")
    ap.add_argument("--band", type=int, default=BAND,
                    help="rainbow: rows averaged on either side of its row")
    ap.add_argument("--frac", type=float, default=FRAC,
                    help="rainbow: beam-only luminance above this fraction of its row's peak")
    ap.add_argument("--common-args", default="", help="appended to every config's arguments")
    a = ap.parse_args()
    if a.seeds < 2:
        raise SystemExit("--seeds must be at least 2 (a sample variance)")
    configs = []
    for c in a.config or DEFAULT_CONFIGS:
        name, sep, extra = c.partition("=")
        if not sep or not name:
            raise SystemExit(f"--config {c!r}: expected NAME=EXTRA_ARGS")
        configs.append((name, shlex.split(extra) + shlex.split(a.common_args)))
    scene = tomllib.loads(a.scene.read_text())
    w, h = int(scene["film"]["width"]), int(scene["film"]["height"])
    spp = a.spp or int(scene["film"].get("spp", 0)) or None
    mask = prism_mask(scene, w, h)
    log(f"prism mask: {int(mask.sum())} px of {w}×{h}")
    res, budget, spp0 = {}, None, None
    with tempfile.TemporaryDirectory() as td:
        outdir = a.keep or Path(td)
        outdir.mkdir(parents=True, exist_ok=True)
        rb_at = rainbow_run(beam_only(a.binary, a.scene, outdir), mask, a.frac)
        log(f"rainbow: row {rb_at[0]}, columns {rb_at[1][0]}-{rb_at[1][-1]}")
        for i, (name, extra) in enumerate(configs):
            if a.equal_spp or i == 0:
                args = extra if "--spp" in extra or spp is None else ["--spp", str(spp), *extra]
            else:
                # equal time: this config's time at the first config's spp, measured on one
                # render (seed 1), scales the spp its renders take
                cal = outdir / f"{name}_calibration.exr"
                t = render(a.binary, a.scene, cal, 1, ["--spp", str(spp0), *extra])
                n = max(1, round(spp0 * budget / t))
                log(f"{name}: {t:.2f} s at {spp0} spp, so {n} spp for {budget:.2f} s")
                args = ["--spp", str(n), *extra]
            res[name] = r = measure(a, name, args, outdir, mask, rb_at)
            budget = budget or r["wall_s"]
            spp0 = spp0 or int(min(r["spp"]))
            if i == 0 and a.overlay:  # the mask tinted cyan, the rainbow run yellow
                o, rb = r["mean_png"].copy(), r["rainbow_mean"]
                o[mask] = 0.5 * o[mask] + [0, 127, 127]
                o[rb["row"], rb["start"] : rb["start"] + rb["length"]] = [255, 255, 0]
                write_png(a.overlay, o)
            del r["mean_png"]

    def fmt_spp(v):
        return "unknown" if None in v else str(min(v)) + (f"-{max(v)}" if max(v) > min(v) else "")

    first = configs[0][0]
    mode = "equal spp" if a.equal_spp else f"equal time (budget {budget:.3f} s from {first})"
    print(f"# Colour noise: {a.scene}, {w}×{h}, seeds 1..{a.seeds}, {mode}")
    print(f"# {cpu_model()}, load {loadavg():.2f}, spectrace {git_head()}")
    print(f"# prism mask: {int(mask.sum())} px\n")
    print(f"{'config':<12} {'wall s':>8} {'render s':>8} {'spp':>8} "
          f"{'chroma var prism':>17} {'chroma var image':>17}  args")
    for n, r in res.items():
        rs = "?" if r["render_s"] is None else f"{r['render_s']:.2f}"
        print(f"{n:<12} {r['wall_s']:>8.2f} {rs:>8} {fmt_spp(r['spp']):>8} "
              f"{r['chroma_var_prism']:>17.5g} {r['chroma_var_image']:>17.5g}  "
              f"{shlex.join(r['args'])}")
    keys = ["row", "length", "coloured", "hue_range", "max_step", "steps_over_15", "clipped2"]
    print(f"\nrainbow (beam light > {a.frac} of its peak, sat > {a.sat}; deg)  " + " ".join(f"{k:>13}" for k in keys))
    for n, r in res.items():
        for lab, rb in (("mean PNG", r["rainbow_mean"]), ("per seed max", r["rainbow_seed_max"])):
            print(f"{n:<12} {lab:<23}" + " ".join(
                f"{rb[k]:>13.1f}" if isinstance(rb[k], float) else f"{rb[k]:>13}" for k in keys))
    ratios = {n: {k: res[first][f"chroma_var_{k}"] / r[f"chroma_var_{k}"]
                  for k in ("prism", "image")} for n, r in list(res.items())[1:]}
    for n, q in ratios.items():
        print(f"\nchroma var ratio {first} ÷ {n}: prism {q['prism']:.3g}, image {q['image']:.3g}")
    if a.json:
        a.json.write_text(json.dumps(dict(
            scene=str(a.scene), size=[w, h], seeds=a.seeds, mode=mode, budget_s=budget,
            mask_px=int(mask.sum()), cpu=cpu_model(), spectrace=git_head(), configs=res,
            ratios=ratios), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
