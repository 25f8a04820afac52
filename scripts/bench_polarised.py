#!/usr/bin/env python3
"""Cost of polarised rendering (issue 28): time per sample of a scene rendered polarised against
the same scene rendered unpolarised, in the same run.

Usage (from the repository root):

    cargo build --release
    python3 scripts/bench_polarised.py [--spp 64,256] [--repeats 3] [--integrator bdpt] [SCENE ...]

Default scenes: the spectral Cornell box `scenes/cornell.toml` at 128 × 128 (diffuse only:
every bounce depolarises) and Mitsuba's `integrator_stokes_cbox.xml` (tests/reference/mitsuba-data, at
res 128: two glass spheres and a conductor, so paths carry full Mueller matrices). Each scene is
rendered with its integrator unpolarised and with `polarised = true` (a TOML copy with the
key added to `[integrator]`; for the Mitsuba scene its `stokes` wrapper decides, and the
unpolarised run unwraps it), alternately, `--repeats` times; the time per sample is the
render time the EXR records (`spectrace:renderTimeSeconds`) over width × height × spp, the
minimum over the repeats. Prints the ratio polarised ÷ unpolarised (target ≤ 1.6).
`--integrator` renders both with `path` (the default), `bdpt` or `light` (light paths per
pixel for its samples).
"""
import argparse
import pathlib
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_common import read_exr, loadavg, cpu_model  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
BIN = ROOT / "target" / "release" / "spectrace"
CBOX = ROOT / "tests/reference/mitsuba-data/docs/scenes/integrator_stokes_cbox.xml"
RES = 128


def variants(scene):
    """(unpolarised, polarised) scene files and extra arguments."""
    text = scene.read_text()
    if scene.suffix == ".toml":
        # a film of RES × RES (the time per sample does not depend on it, the benchmark's
        # time does)
        text = re.sub(r"(?m)^width = \d+", f"width = {RES}", text)
        text = re.sub(r"(?m)^height = \d+", f"height = {RES}", text)
        pol = re.sub(r"\[integrator\]\n", "[integrator]\npolarised = true\n", text, count=1)
        assert pol != text, "the scene needs an [integrator] table"
        # beside the original, so that its relative paths resolve
        un = scene.parent / ("_bench_" + scene.name)
        un.write_text(text)
        p = scene.parent / ("_bench_" + scene.stem + "_polarised.toml")
        p.write_text(pol)
        return un, p, []
    un = re.sub(r'<integrator type="stokes">\s*(<integrator.*?</integrator>)\s*</integrator>',
                r"\1", text, flags=re.S)
    p = scene.parent / ("_bench_unpolarised_" + scene.name)
    p.write_text(un)
    return p, scene, ["-D", "res=128"]


def seconds_per_sample(scene, args, spp):
    out = pathlib.Path(tempfile.gettempdir()) / "bench_polarised.exr"
    subprocess.run([str(BIN), "render", str(scene), "-o", str(out), "--quiet", "--spp", str(spp)]
                   + args, check=True, stderr=subprocess.DEVNULL)
    chans, attrs = read_exr(out)
    h, w = chans["Y"].shape[:2]
    return float(attrs["spectrace:renderTimeSeconds"]) / (w * h * spp)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", default="64,256")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--integrator", default=None)
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    scenes = [pathlib.Path(s) for s in a.scenes] or [ROOT / "scenes/cornell.toml", CBOX]
    print(f"# {cpu_model()}, load {loadavg()}")
    print("# integrator:", a.integrator or "as in the scene")
    print("| scene | spp | unpolarised µs/sample | polarised µs/sample | ratio |")
    print("| --- | --- | --- | --- | --- |")
    for scene in scenes:
        up, pol, extra = variants(scene)
        if a.integrator:
            extra = extra + ["--integrator", a.integrator]
        try:
            for spp in [int(x) for x in a.spp.split(",")]:
                tu, tp = [], []
                for _ in range(a.repeats):
                    tu.append(seconds_per_sample(up, extra, spp))
                    tp.append(seconds_per_sample(pol, extra, spp))
                u, p = min(tu), min(tp)
                print(f"| {scene.name} | {spp} | {u * 1e6:.3f} | {p * 1e6:.3f} | {p / u:.3f} |",
                      flush=True)
        finally:
            for f in (up, pol):
                if f.name.startswith("_bench_"):
                    f.unlink()


if __name__ == "__main__":
    main()
