#!/usr/bin/env python3
"""Efficiency of `bdpt` against `path` (and `light`) on the same scenes, in the same run.

Usage (from the repository root):

    cargo build --release
    python3 scripts/bench_bdpt.py [--spp N] [--threads T] [--repeats R] [--integrators a,b]
                                  [SCENE[@SPP] ...]

Default scenes: the spectral Cornell box tests/reference/cornell/scene.xml and the caustic
scene benchmarks/scenes/prism_room.toml (the default scene's room with the beam replaced by a
small lamp, so that `path` can find the rainbow too, slowly). Needs: pip install OpenImageIO
numpy.

Definitions (as in scripts/bench_efficiency.py):
  * relative variance per sample: two renders with seeds A and B at N spp,
        var = mean_pixels((Y_A - Y_B)^2) / 2 * N,  relative var = var / mean_pixels((Y_A+Y_B)/2)^2;
  * time per sample = render time (the EXR's spectrace:renderTimeSeconds) / (W * H * N);
  * efficiency = 1 / (relative variance per sample * time per sample), 1/s: higher is better;
  * ratio = efficiency / path's efficiency on the same scene in the same run (> 1: better than
    path; its inverse is the time `path` needs for the same error relative to this one).
Both integrators are unbiased, so equal variance means equal error. The variance of `path` on
caustics is heavy-tailed; two images underestimate it, which favours `path`.
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
DEFAULT = ["tests/reference/cornell/scene.xml@64", "benchmarks/scenes/prism_room.toml@16"]


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
        scene, _, spp = spec.partition("@")
        spp = args.spp or int(spp or 16)
        eff = {}
        for integrator in integrators:
            tps, rv = [], []
            for r in range(args.repeats):
                a, ta = render(scene, integrator, spp, 2 * r + 1, args.threads, out)
                b, tb = render(scene, integrator, spp, 2 * r + 2, args.threads, out)
                n = a.size * spp
                tps.append((ta + tb) / 2 / n)
                var = np.mean((a - b) ** 2) / 2 * spp
                rv.append(var / np.mean((a + b) / 2) ** 2)
            t, v = float(np.median(tps)), float(np.mean(rv))
            eff[integrator] = 1 / (v * t)
            ratio = eff[integrator] / eff["path"] if "path" in eff else float("nan")
            print(f"| {pathlib.Path(scene).parent.name if scene.endswith('scene.xml') else pathlib.Path(scene).stem} | {integrator} | {spp} | {t * 1e6:.3f} | {v:.4g} | {eff[integrator]:.4g} | {ratio:.3f} |",
                  flush=True)
    print(f"# load average {loadavg():.2f} at end")


if __name__ == "__main__":
    main()
