#!/usr/bin/env python3
"""Efficiency of `bdpt` against `path` (and `light`) on the same scenes, in the same run.

Usage (from the repository root):

    cargo build --release
    python3 scripts/bench_bdpt.py [--spp N] [--threads T] [--repeats R] [--integrators a,b]
                                  [SCENE[@SPP[@refR]] ...]

Default scenes: the spectral Cornell box tests/reference/cornell/scene.xml (64 spp) and the
caustic scene benchmarks/scenes/prism_room.toml (16 spp, against a bdpt reference of 1024 spp:
the default scene's room with the beam replaced by a projector's lamp in a black tube, so that
`path` can find the rainbow too, rarely; `python3 scripts/gen_prism_scene.py --benchmark`).
Needs: pip install OpenImageIO numpy.

Definitions (as in scripts/bench_efficiency.py):
  * relative variance per sample: two renders with seeds A and B at N spp,
        var = mean_pixels((Y_A - Y_B)^2) / 2 * N,  relative var = var / mean_pixels((Y_A+Y_B)/2)^2;
  * time per sample = render time (the EXR's spectrace:renderTimeSeconds) / (W * H * N);
  * efficiency = 1 / (relative variance per sample * time per sample), 1/s: higher is better;
  * ratio = efficiency / path's efficiency on the same scene in the same run (> 1: better than
    path; its inverse is the time `path` needs for the same error relative to this one).
Both integrators are unbiased, so equal variance means equal error. The variance of `path` on
caustics is heavy-tailed and two images do not see it (the rainbow is simply missing from both),
so a scene given as SCENE@SPP@refR is measured against a reference instead: `bdpt` at R spp
(seed 1000, cached in target/bench_bdpt/), and
    relative error per sample = (mean_pixels((Y - Y_ref)^2) - var_ref) / mean_pixels(Y_ref)^2 * N,
the mean over the A and B images, with var_ref the reference's own variance (bdpt's variance
per sample from its A and B images over R). For an unbiased estimator this is the relative
variance per sample again, measured now with the caustic.
"""
import argparse
import pathlib
import subprocess
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_common import read_exr, loadavg, cpu_model  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
BIN = ROOT / "target" / "release" / "spectrace"
DEFAULT = ["tests/reference/cornell/scene.xml@64", "benchmarks/scenes/prism_room.toml@16@ref1024"]


def render(scene, integrator, spp, seed, threads, out):
    exr = out / f"{pathlib.Path(scene).stem}_{integrator}_{seed}.exr"
    subprocess.run([str(BIN), "render", str(ROOT / scene), "--integrator", integrator, "--spp", str(spp),
                    "--seed", str(seed), "--threads", str(threads), "-o", str(exr),
                    "--png", str(exr.with_suffix(".png")), "--quiet"], check=True,
                   stderr=subprocess.DEVNULL)
    ch, attrs = read_exr(exr)
    return ch["Y"].astype(np.float64), float(attrs["spectrace:renderTimeSeconds"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenes", nargs="*", default=DEFAULT)
    ap.add_argument("--spp", type=int, default=None, help="override every scene's spp")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--integrators", default="path,bdpt")
    args = ap.parse_args()
    out = ROOT / "target" / "bench_bdpt"
    out.mkdir(parents=True, exist_ok=True)
    integrators = args.integrators.split(",")
    print(f"# {cpu_model()}, {args.threads} threads, load average {loadavg():.2f} at start")
    print("| scene | integrator | spp | time per sample (µs) | rel. variance per sample | efficiency (1/s) | ratio to path |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for spec in args.scenes:
        parts = spec.split("@")
        scene = parts[0]
        spp = args.spp or int(parts[1] if len(parts) > 1 else 16)
        ref_spp = int(parts[2][3:]) if len(parts) > 2 and parts[2].startswith("ref") else 0
        ref = None
        if ref_spp:
            ref_dir = out / f"ref{ref_spp}"
            ref_dir.mkdir(exist_ok=True)
            ref, _ = render(scene, "bdpt", ref_spp, 1000, args.threads, ref_dir)
            var_ref_per_sample = None
        raw = {}
        for integrator in integrators:
            tps, rv = [], []
            for r in range(args.repeats):
                a, ta = render(scene, integrator, spp, 2 * r + 1, args.threads, out)
                b, tb = render(scene, integrator, spp, 2 * r + 2, args.threads, out)
                n = a.size * spp
                tps.append((ta + tb) / 2 / n)
                var = np.mean((a - b) ** 2) / 2 * spp
                if ref is None:
                    rv.append(var / np.mean((a + b) / 2) ** 2)
                else:
                    if integrator == "bdpt":
                        var_ref_per_sample = var
                    mse = (np.mean((a - ref) ** 2) + np.mean((b - ref) ** 2)) / 2
                    rv.append(mse * spp / np.mean(ref) ** 2)
            raw[integrator] = (float(np.median(tps)), rv)
        if ref is not None:
            if var_ref_per_sample is None:
                sys.exit("a reference-based scene needs bdpt among the integrators (for var_ref)")
            rv_ref = var_ref_per_sample / ref_spp / np.mean(ref) ** 2 * spp
            print(f"# {scene}: reference bdpt at {ref_spp} spp; its relative variance per sample of the "
                  f"benchmark's spp, subtracted: {rv_ref:.4g}")
            raw = {k: (t, [x - rv_ref for x in rv]) for k, (t, rv) in raw.items()}
        eff = {k: 1 / (float(np.mean(rv)) * t) for k, (t, rv) in raw.items()}
        name = pathlib.Path(scene).parent.name if scene.endswith("scene.xml") else pathlib.Path(scene).stem
        for integrator, (t, rv) in raw.items():
            ratio = eff[integrator] / eff["path"] if "path" in eff else float("nan")
            print(f"| {name} | {integrator} | {spp} | {t * 1e6:.3f} | {float(np.mean(rv)):.4g} | "
                  f"{eff[integrator]:.4g} | {ratio:.3f} |", flush=True)
    print(f"# load average {loadavg():.2f} at end")


if __name__ == "__main__":
    main()
