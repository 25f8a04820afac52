#!/usr/bin/env python3
"""Benchmark spectrace against Mitsuba 3 on the spectral Cornell box (scenes/cornell.toml).

How to run (from the repository root):

    pip install -r scripts/bench-requirements.txt
    # optional, for Mitsuba's llvm_ad_spectral variant (Debian 12):
    #   apt-get update && apt-get install -y libllvm19
    export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1
    python3 scripts/bench_mitsuba.py

Options: --spp 1,4,16,64 (the ladder), --ref-spp 512 (Mitsuba's reference; --ref-spp-spectrace
for spectrace's, default the same), --variants
scalar_spectral,llvm_ad_spectral, --skip-spectrace, --target-relmse 1e-2, --fresh (ignore cached
references). `python3 scripts/bench_mitsuba.py --help` lists them all. If a Mitsuba variant
cannot start (e.g. Dr.Jit finds no libLLVM), or spectrace fails to build or render, that part is
skipped with a note in the report, the rest runs, and the exit code is 1. The run recorded in
benchmarks/mitsuba_cornell.md used `--ref-spp 512 --ref-spp-spectrace 384` (about 9 minutes on
the 2-core machine).

What it does:
  * Builds, through Mitsuba's Python API only, the scene equivalent to scenes/cornell.toml:
    the OBJ meshes of scenes/meshes/ scaled from millimetres to metres; a perspective camera at
    (278, 273, -800) mm looking at (278, 273, 0) mm, up +y, horizontal fov
    2·atan(25 / (2·35)) = 39.31°; a 512×512 film (XYZ pixels, box filter, see below);
    `diffuse` BSDFs with the ColorChecker (N. Ohta) spectra white-9-5, red and green from
    spectra/colorchecker/colorchecker_n_ohta.csv (wrapped in `twosided` for the five walls, which
    the toml marks two_sided); the ceiling light quad as a one-sided `area` emitter whose radiance
    is k·D65(λ) with D65 from spectra/illuminants/cie_d65.csv and
        k = 60 W / (π · A · ∫_360^830 D65 dλ),   A = 0.130 m × 0.105 m = 0.01365 m²,
    the integral taken over the table with linear interpolation (the table stops at 780 nm and
    both renderers read it as 0 beyond), so that the numbers are spectrace's radiance in
    W·m⁻²·sr⁻¹·nm⁻¹ for its "60 W" light; an `independent` sampler; the `path` integrator.
  * Depth mapping. spectrace's `max_depth` counts scattering events (bounces): max_depth = 16
    lets a path have 16 bounces, i.e. 17 segments. Mitsuba's `max_depth` is the longest path
    length in segments (1 = emitters seen directly, 2 = direct illumination). So
    Mitsuba max_depth = spectrace max_depth + 1 = 17. Russian roulette differs (Mitsuba starts
    at rr_depth = 5, spectrace after the first bounce); both are unbiased.
  * Pixel filter. spectrace's default is a Gaussian (σ = 0.5 px) applied by importance
    sampling: each sample lands in one pixel only. Mitsuba's default Gaussian splats each sample
    over a 4×4-pixel footprint, which averages neighbouring samples and would lower its
    per-pixel error for free. Mitsuba here uses its `box` filter (one sample, one pixel), so the
    per-pixel noise of the two renderers compares like with like.
  * Renders a ladder of spp with each renderer, timing the render only (Mitsuba: wall clock
    around mi.render + dr.eval/dr.sync_thread, after one warm-up render, in a worker process per
    variant; spectrace: `target/release/spectrace render scenes/cornell.toml --spp N --quiet`
    after `cargo build --release`, time read from the EXR attribute
    `spectrace:renderTimeSeconds`). The ladder is interleaved (Mitsuba variants and spectrace
    at each spp in turn) so that CPU contention from other processes hits all of them alike.
  * Renders one high-spp reference per renderer, as two independent halves of ref_spp/2 spp
    (different seeds from the ladder). They are cached in target/bench/ (gitignored) under a key
    of the scene inputs and, for spectrace, the binary's hash; --fresh ignores the cache.
  * Error: relative MSE of luminance Y against the renderer's OWN reference,
        relMSE = mean_pixels (x − ref)² / (ref² + 1e-2 · mean(ref)²),
    so that no unit bridge is needed. A reference of R spp adds its own noise (≈ relMSE_1spp / R)
    to every measurement; the two halves estimate it model-free, since
    E[(A − B)²] = 4 · Var(ref): the table shows relMSE with that term subtracted ("relMSE") and
    the raw value.
  * Equal-error comparison: for each renderer/variant, fit relMSE = c / t (slope fixed at −1,
    least squares in log space over the ladder points with spp ≥ 4), then report the time to
    reach --target-relmse and the speed ratio t_mitsuba / t_spectrace at that error (> 1: spectrace
    is faster).
  * Cross-check of the absolute scale: Mitsuba's film reports XYZ / ∫ȳ, spectrace's Y is in
    cd/m², so for the same radiance numbers Y_spectrace = 683.002 · 106.856895 · Y_mitsuba
    = 72 983.0 · Y_mitsuba (PHYSICS.md). The script prints mean(Y_st,ref) / (72 983.0 ·
    mean(Y_mi,ref)), which should be 1 within the references' noise; the error metric itself is
    never rescaled. Mitsuba 3.9.1's own constant is MI_CIE_Y_NORMALIZATION = 1/106.7502 rather
    than 1/106.856895, which moves that ratio to 0.9990 for a perfect match; the script prints
    the ratio with that constant too.

Prints a Markdown report on stdout and writes target/bench/results.json. Uses the Python API of
Mitsuba only (no Mitsuba code is copied here).
"""

from __future__ import annotations

import argparse
import datetime
import hashlib
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from bench_common import cpu_model, loadavg, read_exr

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT / "target" / "bench"
SCENE_TOML = ROOT / "scenes" / "cornell.toml"
MESHES = ROOT / "scenes" / "meshes"
COLORCHECKER = ROOT / "spectra" / "colorchecker" / "colorchecker_n_ohta.csv"
D65 = ROOT / "spectra" / "illuminants" / "cie_d65.csv"
SPECTRACE = ROOT / "target" / "release" / "spectrace"

# Scene constants mirrored from scenes/cornell.toml (checked against it in check_toml()).
WIDTH = HEIGHT = 512
ST_MAX_DEPTH = 16
MI_MAX_DEPTH = ST_MAX_DEPTH + 1  # Mitsuba counts path segments, spectrace counts bounces
LIGHT_POWER_W = 60.0
LIGHT_AREA_M2 = 0.130 * 0.105
LAMBDA_MIN, LAMBDA_MAX = 360.0, 830.0
EYE_MM = (278.0, 273.0, -800.0)
TARGET_MM = (278.0, 273.0, 0.0)
FOV_X_DEG = math.degrees(2.0 * math.atan(25.0 / (2.0 * 35.0)))
KM_TIMES_YBAR = 683.002 * 106.856895  # = 72 983.0 (PHYSICS.md, "Comparing with Mitsuba 3")

# (shape file stem, material, two-sided) as in scenes/cornell.toml
SHAPES = [
    ("cbox_floor", "white-9-5", True),
    ("cbox_ceiling", "white-9-5", True),
    ("cbox_back", "white-9-5", True),
    ("cbox_green", "green", True),
    ("cbox_red", "red", True),
    ("cbox_shortblock", "white-9-5", False),
    ("cbox_tallblock", "white-9-5", False),
    ("cbox_light", "white-9-5", False),  # also the emitter
]

LADDER_SEED_BASE = 1  # ladder renders use seed = LADDER_SEED_BASE + index
REF_SEED_BASE = 100_000  # reference passes use seeds from here on
WARMUP_SEED = 999_999
REF_PASS_SPP = 64  # Mitsuba reference passes (bounds the LLVM variant's wavefront memory)
EPS_REL = 1e-2


# --------------------------------------------------------------------------- spectra


def read_csv_columns(path: Path) -> dict[str, np.ndarray]:
    rows = [
        ln.strip().split(",")
        for ln in path.read_text().splitlines()
        if ln.strip() and not ln.startswith("#")
    ]
    header, data = rows[0], np.array(rows[1:], dtype=np.float64)
    return {name: data[:, i] for i, name in enumerate(header)}


def spectrum_pairs(path: Path, column: str, scale: float = 1.0) -> list[tuple[float, float]]:
    cols = read_csv_columns(path)
    lam = cols["wavelength_nm"]
    return [(float(l), float(v) * scale) for l, v in zip(lam, cols[column])]


def integrate_table(lam: np.ndarray, val: np.ndarray, lo: float, hi: float) -> float:
    """∫_lo^hi of the linear interpolant of (lam, val), zero outside the table.

    The table jumps to zero at its ends (as in both renderers), so the interval is clipped to
    the table's domain first: a grid point past the end would add a spurious ramp to zero.
    """
    lo, hi = max(lo, float(lam[0])), min(hi, float(lam[-1]))
    if not hi > lo:
        return 0.0
    grid = np.union1d(lam[(lam > lo) & (lam < hi)], [lo, hi])
    f = np.interp(grid, lam, val)
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(grid)))


def d65_scale() -> tuple[float, float]:
    """k such that k·D65 is the radiance (W·m⁻²·sr⁻¹·nm⁻¹) of a 60 W one-sided Lambertian quad."""
    cols = read_csv_columns(D65)
    integral = integrate_table(cols["wavelength_nm"], cols["value"], LAMBDA_MIN, LAMBDA_MAX)
    return LIGHT_POWER_W / (math.pi * LIGHT_AREA_M2 * integral), integral


def check_toml() -> None:
    """Fails loudly if scenes/cornell.toml no longer says what this script mirrors."""
    import tomllib

    t = tomllib.loads(SCENE_TOML.read_text())
    assert t["scene"]["length_unit"] == "mm"
    assert tuple(t["camera"]["eye"]) == EYE_MM and tuple(t["camera"]["target"]) == TARGET_MM
    assert t["camera"]["focal_length"] == "35 mm" and t["camera"]["sensor_width"] == "25 mm"
    assert t["film"]["width"] == WIDTH and t["film"]["height"] == HEIGHT
    assert t["integrator"]["type"] == "path"
    assert t["integrator"]["max_depth"] == ST_MAX_DEPTH
    mats = {k: v["reflectance"].split(":", 1)[1] for k, v in t["materials"].items()}
    shapes = [
        (Path(s["file"]).stem, mats[s["material"]], bool(s.get("two_sided", False)))
        for s in t["shapes"]
    ]
    assert shapes == SHAPES, shapes
    em = t["shapes"][-1]["emission"]
    assert em == {"spectrum": "cie-d65", "power": "60 W"}, em


def input_key(extra: bytes = b"") -> str:
    h = hashlib.sha256()
    for p in [SCENE_TOML, COLORCHECKER, D65, *sorted(MESHES.glob("*.obj"))]:
        h.update(p.read_bytes())
    h.update(f"{MI_MAX_DEPTH} {WIDTH} {HEIGHT} box".encode())
    h.update(extra)
    return h.hexdigest()[:12]


# --------------------------------------------------------------------------- Mitsuba worker


def mitsuba_scene_dict(mi) -> dict:
    k, _ = d65_scale()
    to_metres = mi.ScalarTransform4f().scale(0.001)

    def diffuse(patch: str, two_sided: bool) -> dict:
        bsdf = {
            "type": "diffuse",
            "reflectance": {"type": "spectrum", "value": spectrum_pairs(COLORCHECKER, patch)},
        }
        return {"type": "twosided", "bsdf": bsdf} if two_sided else bsdf

    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": MI_MAX_DEPTH},
        "sensor": {
            "type": "perspective",
            "fov": FOV_X_DEG,
            "fov_axis": "x",
            "near_clip": 0.01,
            "far_clip": 100.0,
            "to_world": mi.ScalarTransform4f().look_at(
                origin=[c * 1e-3 for c in EYE_MM],
                target=[c * 1e-3 for c in TARGET_MM],
                up=[0, 1, 0],
            ),
            "film": {
                "type": "hdrfilm",
                "width": WIDTH,
                "height": HEIGHT,
                "pixel_format": "xyz",
                "rfilter": {"type": "box"},
            },
            "sampler": {"type": "independent"},
        },
    }
    for stem, patch, two_sided in SHAPES:
        shape = {
            "type": "obj",
            "filename": str(MESHES / f"{stem}.obj"),
            "face_normals": True,
            "to_world": to_metres,
            "bsdf": diffuse(patch, two_sided),
        }
        if stem == "cbox_light":
            shape["emitter"] = {
                "type": "area",
                "radiance": {"type": "spectrum", "value": spectrum_pairs(D65, "value", k)},
            }
        scene[stem] = shape
    return scene


def mitsuba_worker(variant: str) -> None:
    """Line protocol on stdin/stdout: '@@' + JSON. Renders on request, writes XYZ EXRs."""
    out = sys.stdout
    sys.stdout = sys.stderr  # keep library chatter off the protocol channel

    def reply(obj: dict) -> None:
        out.write("@@" + json.dumps(obj) + "\n")
        out.flush()

    try:
        import drjit as dr
        import mitsuba as mi

        mi.set_variant(variant)
        scene = mi.load_dict(mitsuba_scene_dict(mi))

        def render(spp: int, seed: int):
            t0 = time.perf_counter()
            img = mi.render(scene, spp=spp, seed=seed)
            dr.eval(img)
            dr.sync_thread()
            return img, time.perf_counter() - t0

        _, warm = render(1, WARMUP_SEED)  # thread pool start-up, JIT compilation (LLVM)
        reply(
            {
                "ready": True,
                "mitsuba": mi.__version__,
                "drjit": dr.__version__,
                "cie_y_normalization": float(mi.MI_CIE_Y_NORMALIZATION),
                "warmup_seconds": warm,
            }
        )
    except Exception as e:  # noqa: BLE001 — report any start-up failure to the driver
        reply({"ready": False, "error": f"{type(e).__name__}: {e}"})
        return
    for line in sys.stdin:
        req = json.loads(line)
        if req.get("quit"):
            break
        img, secs = render(req["spp"], req["seed"])
        bmp = mi.Bitmap(np.array(img), pixel_format=mi.Bitmap.PixelFormat.XYZ)
        bmp.write(req["out"])
        reply({"seconds": secs})


class MitsubaWorker:
    def __init__(self, variant: str):
        self.variant = variant
        self.proc = subprocess.Popen(
            [sys.executable, __file__, "--mitsuba-worker", variant],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            cwd=ROOT,
        )
        self.info = self._read()

    def _read(self) -> dict:
        for line in self.proc.stdout:
            if line.startswith("@@"):
                return json.loads(line[2:])
        raise RuntimeError(f"Mitsuba worker {self.variant} exited (code {self.proc.wait()})")

    def render(self, spp: int, seed: int, out: Path) -> float:
        self.proc.stdin.write(json.dumps({"spp": spp, "seed": seed, "out": str(out)}) + "\n")
        self.proc.stdin.flush()
        return self._read()["seconds"]

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.stdin.write(json.dumps({"quit": True}) + "\n")
            self.proc.stdin.flush()
            self.proc.wait(timeout=60)


# --------------------------------------------------------------------------- images


def write_xyz_exr(path: Path, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> None:
    import OpenImageIO as oiio

    spec = oiio.ImageSpec(x.shape[1], x.shape[0], 3, "float")
    spec.channelnames = ("X", "Y", "Z")
    out = oiio.ImageOutput.create(str(path))
    if out is None or not out.open(str(path), spec):
        raise RuntimeError(f"cannot write {path}: {oiio.geterror()}")
    out.write_image(np.stack([x, y, z], axis=-1).astype(np.float32))
    out.close()


def rel_mse(x: np.ndarray, ref: np.ndarray) -> float:
    return float(np.mean((x - ref) ** 2 / (ref**2 + EPS_REL * ref.mean() ** 2)))


def ref_noise(a: np.ndarray, b: np.ndarray, ref: np.ndarray) -> float:
    """Var(ref) in the relMSE's weighting, from two independent halves: E[(A−B)²] = 4·Var(ref)."""
    return float(np.mean((a - b) ** 2 / 4.0 / (ref**2 + EPS_REL * ref.mean() ** 2)))


# --------------------------------------------------------------------------- spectrace


def spectrace_render(spp: int, seed: int, out: Path) -> tuple[float, float]:
    """Returns (render seconds from the EXR header, process wall clock)."""
    cmd = [str(SPECTRACE), "render", str(SCENE_TOML), "--spp", str(spp), "--seed", str(seed)]
    cmd += ["--quiet", "-o", str(out)]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(
            f"`{' '.join(cmd)}` failed with exit code {r.returncode}:\n{r.stderr.strip()}"
        )
    _, attrs = read_exr(out)
    return float(attrs["spectrace:renderTimeSeconds"]), wall


def file_sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()[:12]


# --------------------------------------------------------------------------- driver


def fit_c(points: list[dict]) -> float:
    """relMSE = c / t, least squares in log space over the points with spp ≥ 4."""
    use = [p for p in points if p["spp"] >= 4 and p["relmse"] > 0] or points
    return float(math.exp(np.mean([math.log(p["relmse"] * p["seconds"]) for p in use])))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--spp", default="1,4,16,64", help="spp ladder, comma-separated")
    ap.add_argument("--ref-spp", type=int, default=512, help="spp of the Mitsuba reference")
    ap.add_argument(
        "--ref-spp-spectrace", type=int, default=None, help="spp of spectrace's (default: --ref-spp)"
    )
    ap.add_argument("--variants", default="scalar_spectral,llvm_ad_spectral")
    ap.add_argument("--skip-spectrace", action="store_true")
    ap.add_argument("--no-build", action="store_true", help="skip cargo build --release")
    ap.add_argument("--target-relmse", type=float, default=1e-2)
    ap.add_argument("--fresh", action="store_true", help="ignore cached references")
    ap.add_argument("--mitsuba-worker", metavar="VARIANT", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.mitsuba_worker:
        mitsuba_worker(args.mitsuba_worker)
        return 0

    check_toml()
    ladder = [int(s) for s in args.spp.split(",")]
    ref_spp = {"mitsuba": args.ref_spp, "spectrace": args.ref_spp_spectrace or args.ref_spp}
    BENCH.mkdir(parents=True, exist_ok=True)
    notes: list[str] = []
    k, d65_int = d65_scale()
    t_start = time.time()
    log = lambda *a: print(*a, file=sys.stderr, flush=True)  # noqa: E731
    log(f"k = {k:.6e} (∫D65 = {d65_int:.4f}), Mitsuba max_depth = {MI_MAX_DEPTH}")

    # spectrace build
    st_ok = not args.skip_spectrace
    st_version = ""
    if st_ok and not args.no_build:
        log("cargo build --release ...")
        r = subprocess.run(["cargo", "build", "--release"], cwd=ROOT, capture_output=True, text=True)
        if r.returncode != 0:
            notes.append(f"cargo build --release failed:\n{r.stderr.strip()[-2000:]}")
            st_ok = False
    if st_ok:
        st_version = subprocess.run(
            [str(SPECTRACE), "--version"], capture_output=True, text=True
        ).stdout.strip()
    git_head = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
    ).stdout.strip()

    # Mitsuba workers
    workers: list[MitsubaWorker] = []
    mi_versions = {}
    mi_y_norm = 1.0 / 106.856895
    for v in [s for s in args.variants.split(",") if s]:
        if v.startswith("llvm") and not os.environ.get("DRJIT_LIBLLVM_PATH"):
            log(f"note: DRJIT_LIBLLVM_PATH is not set; Dr.Jit will search for libLLVM itself")
        log(f"starting Mitsuba {v} ...")
        w = MitsubaWorker(v)
        if not w.info.get("ready"):
            notes.append(f"Mitsuba variant {v} could not start: {w.info.get('error')}")
            w.proc.wait()
            continue
        mi_versions = {"mitsuba": w.info["mitsuba"], "drjit": w.info["drjit"]}
        mi_y_norm = w.info["cie_y_normalization"]
        log(f"  {v} ready (warm-up 1 spp: {w.info['warmup_seconds']:.2f} s)")
        workers.append(w)
    if not workers:
        notes.append("no Mitsuba variant ran")

    # ladder, interleaved
    results: dict[str, list[dict]] = {w.variant: [] for w in workers}
    if st_ok:
        results["spectrace"] = []
    for i, spp in enumerate(ladder):
        seed = LADDER_SEED_BASE + i
        for w in workers:
            out = BENCH / f"mi_{w.variant}_{spp}.exr"
            la = loadavg()
            secs = w.render(spp, seed, out)
            results[w.variant].append({"spp": spp, "seconds": secs, "load1": la, "file": out})
            log(f"  {w.variant:18s} {spp:5d} spp  {secs:8.2f} s  (load {la:.2f})")
        if st_ok:
            out = BENCH / f"st_{spp}.exr"
            la = loadavg()
            try:
                secs, wall = spectrace_render(spp, seed, out)
            except RuntimeError as e:
                notes.append(f"spectrace render failed: {e}")
                st_ok = False
                results.pop("spectrace", None)
                continue
            results["spectrace"].append(
                {"spp": spp, "seconds": secs, "wall": wall, "load1": la, "file": out}
            )
            log(f"  {'spectrace':18s} {spp:5d} spp  {secs:8.2f} s  (load {la:.2f})")

    # references (two independent halves each), cached
    refs: dict[str, dict] = {}
    if workers:
        w = next((w for w in workers if w.variant.startswith("llvm")), workers[0])
        key = input_key(f"mitsuba {mi_versions.get('mitsuba')} k={k!r}".encode())
        half = max(1, ref_spp["mitsuba"] // 2)
        halves = [BENCH / f"mi_ref_{2 * half}_{key}_{h}.exr" for h in "ab"]
        cached = all(p.exists() for p in halves) and not args.fresh
        secs = 0.0
        if not cached:
            for h, path in enumerate(halves):
                acc, done, j = None, 0, 0
                while done < half:
                    n = min(REF_PASS_SPP, half - done)
                    tmp = BENCH / "mi_ref_pass.exr"
                    secs += w.render(n, REF_SEED_BASE + 1000 * h + j, tmp)
                    c, _ = read_exr(tmp)
                    part = np.stack([c["X"], c["Y"], c["Z"]]) * n
                    acc = part if acc is None else acc + part
                    done, j = done + n, j + 1
                    log(f"  Mitsuba reference half {h}: {done}/{half} spp")
                acc /= half
                write_xyz_exr(path, *acc)
        refs["mitsuba"] = {
            "variant": w.variant,
            "halves": halves,
            "cached": cached,
            "seconds": secs,
            "spp": 2 * half,
        }
    for w in workers:
        w.close()
    if st_ok:
        key = input_key(f"spectrace {file_sha(SPECTRACE)}".encode())
        half = max(1, ref_spp["spectrace"] // 2)
        halves = [BENCH / f"st_ref_{2 * half}_{key}_{h}.exr" for h in "ab"]
        cached = all(p.exists() for p in halves) and not args.fresh
        secs = 0.0
        try:
            if not cached:
                for h, path in enumerate(halves):
                    log(f"  spectrace reference half {h}: {half} spp ...")
                    s, _ = spectrace_render(half, REF_SEED_BASE + 1000 * h, path)
                    secs += s
            refs["spectrace"] = {
                "halves": halves,
                "cached": cached,
                "seconds": secs,
                "spp": 2 * half,
            }
        except RuntimeError as e:
            notes.append(f"spectrace reference render failed: {e}")
            st_ok = False
            results.pop("spectrace", None)

    # errors
    ref_y: dict[str, np.ndarray] = {}
    ref_xyz_mean: dict[str, np.ndarray] = {}
    for name, r in refs.items():
        a, _ = read_exr(r["halves"][0])
        b, _ = read_exr(r["halves"][1])
        ref = 0.5 * (a["Y"] + b["Y"])
        ref_y[name] = ref
        ref_xyz_mean[name] = np.array([0.5 * (a[c] + b[c]).mean() for c in "XYZ"])
        r["noise"] = ref_noise(a["Y"], b["Y"], ref)
    for name, pts in results.items():
        rname = "spectrace" if name == "spectrace" else "mitsuba"
        if rname not in ref_y:
            continue
        for p in pts:
            c, _ = read_exr(p["file"])
            p["relmse_raw"] = rel_mse(c["Y"], ref_y[rname])
            p["relmse"] = p["relmse_raw"] - refs[rname]["noise"]
            p["mean_y"] = float(c["Y"].mean())
            p["file"] = str(Path(p["file"]).relative_to(ROOT))

    # report
    target = args.target_relmse
    fits = {name: fit_c(pts) for name, pts in results.items() if pts and "relmse" in pts[0]}
    lines = []
    lines.append(
        "| renderer / variant | spp | seconds | samples/s | relMSE (Y) | raw relMSE | load (1 min) |"
    )
    lines.append("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, pts in results.items():
        label = "spectrace (path)" if name == "spectrace" else f"Mitsuba {name}"
        for p in pts:
            sps = WIDTH * HEIGHT * p["spp"] / p["seconds"]
            rel = f"{p['relmse']:.3e}" if "relmse" in p else "n/a"
            raw = f"{p['relmse_raw']:.3e}" if "relmse_raw" in p else "n/a"
            lines.append(
                f"| {label} | {p['spp']} | {p['seconds']:.2f} | {sps / 1e6:.3f} M | {rel} | {raw} "
                f"| {p['load1']:.2f} |"
            )
    table = "\n".join(lines)

    eq = []
    if fits:
        eq.append(
            f"| renderer / variant | c = relMSE·t (s) | time to relMSE = {target:g} | "
            "speed ratio at equal error (t_Mitsuba / t_spectrace) |"
        )
        eq.append("| --- | ---: | ---: | ---: |")
        st_t = fits["spectrace"] / target if "spectrace" in fits else None
        for name, c in fits.items():
            t = c / target
            label = "spectrace (path)" if name == "spectrace" else f"Mitsuba {name}"
            ratio = "1 (baseline)" if name == "spectrace" else (
                f"{t / st_t:.2f}" if st_t else "n/a"
            )
            eq.append(f"| {label} | {c:.3e} | {t:.1f} s | {ratio} |")
    eq_table = "\n".join(eq)

    cross = None
    if "mitsuba" in ref_xyz_mean and "spectrace" in ref_xyz_mean:
        ratio_xyz = ref_xyz_mean["spectrace"] / (KM_TIMES_YBAR * ref_xyz_mean["mitsuba"])
        cross = {
            "mean_Y_spectrace_cd_m2": float(ref_xyz_mean["spectrace"][1]),
            "mean_Y_mitsuba": float(ref_xyz_mean["mitsuba"][1]),
            "ratio_Y": float(ratio_xyz[1]),
            "ratio_X": float(ratio_xyz[0]),
            "ratio_Z": float(ratio_xyz[2]),
            # the same with Mitsuba's own normalisation constant instead of PHYSICS.md's ∫ȳ
            "mitsuba_cie_y_integral": 1.0 / mi_y_norm,
            "ratio_Y_mitsuba_constant": float(ratio_xyz[1] * 106.856895 * mi_y_norm),
        }

    out = []
    out.append(f"Date: {datetime.date.today().isoformat()}; machine: {os.cpu_count()} × {cpu_model()}")
    out.append(
        f"Versions: Mitsuba {mi_versions.get('mitsuba', 'n/a')} (Dr.Jit {mi_versions.get('drjit', 'n/a')}), "
        f"{st_version or 'spectrace n/a'} (git {git_head}), Python {platform.python_version()}"
    )
    out.append(
        f"Light: k = {k:.6e} W·m⁻²·sr⁻¹·nm⁻¹ per D65 unit (∫_360^830 D65 = {d65_int:.4f}); "
        f"max_depth: spectrace {ST_MAX_DEPTH} ↔ Mitsuba {MI_MAX_DEPTH}"
    )
    for name, r in refs.items():
        what = "cached" if r["cached"] else f"rendered in {r['seconds']:.0f} s"
        var = f" ({r['variant']})" if "variant" in r else ""
        out.append(
            f"Reference {name}{var}: {r['spp']} spp as two halves of {r['spp'] // 2}, {what}; "
            f"its own noise in relMSE units: {r['noise']:.3e} (subtracted)"
        )
    out.append("")
    out.append(table)
    out.append("")
    if eq_table:
        out.append(eq_table)
        out.append("")
    if cross:
        out.append(
            f"Cross-check: mean Y of the references, spectrace {cross['mean_Y_spectrace_cd_m2']:.2f} cd/m², "
            f"Mitsuba {cross['mean_Y_mitsuba']:.6f}; Y_spectrace / (72 983.0 · Y_Mitsuba) = "
            f"{cross['ratio_Y']:.4f} (X: {cross['ratio_X']:.4f}, Z: {cross['ratio_Z']:.4f}); "
            f"with Mitsuba's own constant MI_CIE_Y_NORMALIZATION = 1/{cross['mitsuba_cie_y_integral']:.4f} "
            f"instead of 1/106.856895: {cross['ratio_Y_mitsuba_constant']:.4f}"
        )
    for n in notes:
        out.append("")
        out.append("Note: " + n)
    out.append("")
    out.append(f"Total benchmark time: {time.time() - t_start:.0f} s")
    print("\n".join(out))

    def plain(o):
        if isinstance(o, Path):
            return str(o.relative_to(ROOT))
        raise TypeError(type(o))

    (BENCH / "results.json").write_text(
        json.dumps(
            {
                "ladder": results,
                "references": refs,
                "fits_c": fits,
                "target_relmse": target,
                "cross_check": cross,
                "k": k,
                "versions": mi_versions | {"spectrace": st_version, "git": git_head},
                "notes": notes,
            },
            indent=2,
            default=plain,
        )
    )
    return 0 if not notes else 1


if __name__ == "__main__":
    sys.exit(main())
