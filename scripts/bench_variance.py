#!/usr/bin/env python3
"""Variance per sample and efficiency on issue 25's glass-sphere scene: spectrace against
Mitsuba 3.9.1 (same XML) and Blender Cycles (the same geometry built through `bpy`).

How to run (from the repository root):

    pip install -r scripts/bench-requirements.txt   # mitsuba 3.9.1, numpy, OpenImageIO
    # optional, Blender's Cycles (a tool, not a dependency; Python 3.11; bpy pins numpy 1.26, so
    # it gets its own environment):
    python3 -m venv /opt/bpyenv && /opt/bpyenv/bin/pip install bpy
    cargo build --release
    python3 scripts/bench_variance.py               # --spp 64 --threads 2 --repeats 1

Options: --scene PATH (default benchmarks/scenes/glass_sphere_lamp.xml; Cycles only knows this
one), --spp N, --threads T, --repeats R, --configs spectrace,mitsuba,cycles (any subset, also
spectrace-power and spectrace-uniform: the scene with `light_selection` set so, TOML scenes
only; `mitsuba` is scalar_spectral with ldsampler), --save DIR (keep the images), --blender-python
PATH (the Python that imports bpy; default /opt/bpyenv/bin/python, else this one).

Definitions (as scripts/bench_efficiency.py; Y is luminance):
  * Each configuration renders the scene twice, seeds A and B, N spp each. Over a set of pixels
        relative variance per sample = mean((Y_A − Y_B)²) / 2 × N / mean((Y_A + Y_B)/2)².
  * Regions: the whole image; the floor = the bottom quarter of the rows (all of it directly lit
    floor in this scene); the typical floor pixel = the floor without its brightest 1 % of
    pixels (by (Y_A + Y_B)/2), which drops the caustic.
  * Efficiency = samples per second ÷ relative variance per sample (whole image), render time
    only (spectrace's EXR attribute; Mitsuba's and Cycles' wall clock around the render call,
    after a warm-up render).

Cycles: Blender's Python module, CPU, `threads` threads, path tracing with max 12 bounces
(all kinds), no adaptive sampling, no denoising, no clamping, no light tree change (its
default, on), filter `BOX` of width 1 px, black world, 16-bit-free float output read from the
render result. Its lamp is a point light of radius 0.5 m (a sphere light since Blender 4.0)
whose power is set so its radiance matches; the sphere is a UV sphere of 256 × 128 faces,
smooth shaded. Cycles renders linear Rec. 709 RGB; Y = 0.2126 R + 0.7152 G + 0.0722 B.

Prints a Markdown table on stdout (progress on stderr) and writes target/bench/variance.json.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_efficiency as be  # noqa: E402
from bench_common import cpu_model, loadavg  # noqa: E402

ROOT = be.ROOT
DEFAULT_SCENE = ROOT / "benchmarks" / "scenes" / "glass_sphere_lamp.xml"
OUT_JSON = ROOT / "target" / "bench" / "variance.json"
SEED_BASE = 11


def log(*a) -> None:
    print(*a, file=sys.stderr, flush=True)


def regions(shape: tuple[int, int], mean: np.ndarray) -> dict[str, np.ndarray]:
    """Boolean masks: whole image, the floor (bottom quarter), the floor's typical pixels."""
    h, w = shape
    whole = np.ones(shape, bool)
    floor = np.zeros(shape, bool)
    floor[h - h // 4 :, :] = True
    cut = np.quantile(mean[floor], 0.99)
    typical = floor & (mean <= cut)
    return {"whole image": whole, "floor": floor, "typical floor pixel": typical}


def rel_var(a: np.ndarray, b: np.ndarray, spp: int, mask: np.ndarray) -> float:
    d = ((a - b) ** 2)[mask]
    m = (0.5 * (a + b))[mask]
    mean = float(np.mean(m))
    return float(np.mean(d)) / 2.0 * spp / mean**2 if mean > 0 else float("nan")


# --------------------------------------------------------------------------- Cycles


CYCLES_SCRIPT = r"""
import bpy, json, math, sys, time
import numpy as np
from mathutils import Vector
args = json.loads(sys.argv[-1])
bpy.ops.wm.read_factory_settings(use_empty=True)
sc = bpy.context.scene
sc.render.engine = 'CYCLES'
cy = sc.cycles
cy.device = 'CPU'
cy.samples = args['spp']
cy.use_adaptive_sampling = False
cy.use_denoising = False
cy.sample_clamp_direct = 0.0
cy.sample_clamp_indirect = 0.0
cy.max_bounces = 12
cy.diffuse_bounces = cy.glossy_bounces = cy.transmission_bounces = 12
cy.transparent_max_bounces = 12
cy.caustics_reflective = True
cy.caustics_refractive = True
cy.blur_glossy = 0.0
cy.pixel_filter_type = 'BOX'
cy.filter_width = 1.0
sc.render.threads_mode = 'FIXED'
sc.render.threads = args['threads']
sc.render.resolution_x = args['res']
sc.render.resolution_y = args['res']
sc.render.resolution_percentage = 100
sc.render.film_transparent = False
sc.view_settings.view_transform = 'Standard'
world = bpy.data.worlds.new('black'); world.use_nodes = True
world.node_tree.nodes['Background'].inputs['Strength'].default_value = 0.0
sc.world = world

def material(name, kind, **inputs):
    m = bpy.data.materials.new(name); m.use_nodes = True
    nt = m.node_tree; nt.nodes.clear()
    out = nt.nodes.new('ShaderNodeOutputMaterial')
    b = nt.nodes.new(kind)
    for k, v in inputs.items():
        b.inputs[k].default_value = v
    nt.links.new(b.outputs[0], out.inputs['Surface'])
    return m

# Blender is z-up: the XML's (x, y, z) is Blender's (x, -z, y) with y up -> z up
def bl(x, y, z):
    return Vector((x, z, y))

bpy.ops.mesh.primitive_plane_add(size=10.0, location=bl(0, 0, 0))
bpy.context.object.data.materials.append(
    material('floor', 'ShaderNodeBsdfDiffuse', Color=(0.5, 0.5, 0.5, 1.0)))
bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128, radius=0.5,
                                     location=bl(0, 0.5, 0))
bpy.ops.object.shade_smooth()
bpy.context.object.data.materials.append(
    material('glass', 'ShaderNodeBsdfGlass', IOR=1.5046, Roughness=0.0,
             Color=(1.0, 1.0, 1.0, 1.0)))
light = bpy.data.lights.new('lamp', 'POINT')
light.shadow_soft_size = 0.5
# a sphere light of radius r and radiance L emits P = 4 pi^2 r^2 L (W); Blender's point power
# is that P in its units, so the radiance is the same up to the scale (which cancels)
light.energy = 4.0 * math.pi ** 2 * 0.5 ** 2 * 10.0
lo = bpy.data.objects.new('lamp', light); lo.location = bl(0, 3.5, 0)
sc.collection.objects.link(lo)
cam = bpy.data.cameras.new('cam'); cam.sensor_fit = 'HORIZONTAL'; cam.angle = math.radians(40)
co = bpy.data.objects.new('cam', cam); sc.collection.objects.link(co); sc.camera = co
eye, target = bl(0, 1.5, -4.5), bl(0, 0.9, 0)
co.location = eye
co.rotation_euler = (target - eye).to_track_quat('-Z', 'Z').to_euler()

def render(seed):
    cy.seed = seed
    t0 = time.perf_counter()
    bpy.ops.render.render()
    t = time.perf_counter() - t0
    img = bpy.data.images['Render Result']
    # pixels of the render result: save to EXR and read back (Render Result has no pixels)
    path = args['out'] + f'.{seed}.exr'
    sc.render.image_settings.file_format = 'OPEN_EXR'
    sc.render.image_settings.color_depth = '32'
    img.save_render(path)
    return t, path

render(args['warmup_seed'])
res = []
for s in args['seeds']:
    t, p = render(s)
    res.append({'seconds': t, 'path': p})
print('@@' + json.dumps(res), flush=True)
"""


def blender_python() -> str:
    venv = Path("/opt/bpyenv/bin/python")
    return str(venv) if venv.exists() else sys.executable


BLENDER_PY = blender_python()


def cycles_renders(spp: int, threads: int, res: int, seeds: list[int], tmp: Path) -> list[dict]:
    args = {
        "spp": spp,
        "threads": threads,
        "res": res,
        "seeds": seeds,
        "warmup_seed": 999,
        "out": str(tmp / "cycles"),
    }
    script = tmp / "cycles_scene.py"
    script.write_text(CYCLES_SCRIPT)
    r = subprocess.run(
        [BLENDER_PY, str(script), json.dumps(args)], capture_output=True, text=True
    )
    line = next((x for x in r.stdout.splitlines() if x.startswith("@@")), None)
    if r.returncode != 0 or line is None:
        raise RuntimeError(f"Cycles failed ({r.returncode}):\n{r.stderr[-2000:]}")
    out = []
    for item in json.loads(line[2:]):
        chans, _ = be.read_exr(Path(item["path"]))
        y = sum(w * chans[c] for w, c in zip(be.SRGB_Y, "RGB"))
        out.append({"seconds": item["seconds"], "y": y})
    return out


def cycles_version() -> str:
    r = subprocess.run(
        [BLENDER_PY, "-c", "import bpy; print(bpy.app.version_string)"],
        capture_output=True,
        text=True,
    )
    return r.stdout.strip().splitlines()[-1] if r.returncode == 0 and r.stdout.strip() else ""


def with_selection(scene: Path, kind: str) -> Path:
    """A copy of the TOML `scene` beside it with `[integrator] light_selection = kind`."""
    if scene.suffix != ".toml":
        raise SystemExit("spectrace-power and spectrace-uniform need a TOML scene")
    text = scene.read_text()
    if "light_selection" in text:
        raise SystemExit(f"{scene} sets light_selection already")
    text = text.replace("[integrator]", f'[integrator]\nlight_selection = "{kind}"', 1)
    out = scene.parent / f".{scene.stem}.{kind}.toml"
    out.write_text(text)
    return out


# --------------------------------------------------------------------------- driver


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", type=Path, default=DEFAULT_SCENE)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--configs", default="spectrace,mitsuba,cycles")
    ap.add_argument("--save", type=Path, default=None)
    ap.add_argument("--blender-python", default=None)
    ap.add_argument("--mitsuba-sampler", default="ldsampler",
                    help="Mitsuba's sampler (ldsampler, independent, stratified, multijitter)")
    a = ap.parse_args()
    if a.blender_python:
        global BLENDER_PY
        BLENDER_PY = a.blender_python
    configs = [c.strip() for c in a.configs.split(",") if c.strip()]
    for c in configs:
        if c not in ("spectrace", "spectrace-power", "spectrace-uniform", "mitsuba", "cycles"):
            raise SystemExit(f"unknown configuration {c!r}")
    scene = a.scene.resolve()
    text = scene.read_text()
    w, h = be.film_size(text) if scene.suffix == ".xml" else (0, 0)
    if "cycles" in configs and (scene != DEFAULT_SCENE.resolve() or w != h):
        raise SystemExit("Cycles builds only the default scene (square film)")
    if "cycles" in configs and not cycles_version():
        log("bpy is not importable: Cycles skipped (pip install bpy)")
        configs.remove("cycles")

    results: dict[str, list[dict]] = {c: [] for c in configs}
    skipped = []
    with tempfile.TemporaryDirectory(dir=ROOT / "target") as td:
        tmp = Path(td)
        mts = None
        if "mitsuba" in configs:
            xml = scene.parent / f".{scene.stem}.ldsampler.xml"
            xml.write_text(be.rewrite_xml(text, a.mitsuba_sampler, None))
            mts = be.MitsubaWorker("scalar_spectral", a.threads)
            if not mts.info.get("ready"):
                skipped.append(f"mitsuba: {mts.info.get('error')}")
                configs.remove("mitsuba")
            else:
                r = mts.ask(cmd="load", path=str(xml), spp=a.spp)
                if not r.get("ok"):
                    skipped.append(f"mitsuba: {r.get('error')}")
                    configs.remove("mitsuba")
        try:
            for rep in range(a.repeats):
                seeds = [SEED_BASE + 2 * rep, SEED_BASE + 2 * rep + 1]
                for c in configs:
                    imgs = []
                    if c.startswith("spectrace"):
                        path = scene
                        if c != "spectrace":
                            path = with_selection(scene, c.split("-")[1])
                        try:
                            for s in seeds:
                                t, y = be.spectrace_render(path, a.spp, s, a.threads, tmp / f"s{s}.exr")
                                imgs.append({"seconds": t, "y": y, "spp": a.spp})
                        finally:
                            if path != scene:
                                path.unlink()
                    elif c == "mitsuba":
                        for s in seeds:
                            out = tmp / f"m{s}.npy"
                            r = mts.ask(cmd="render", spp=a.spp, seed=s, out=str(out))
                            if not r.get("ok"):
                                raise RuntimeError(r.get("error"))
                            imgs.append({"seconds": r["seconds"], "y": np.load(out), "spp": r["spp"]})
                    else:
                        for x in cycles_renders(a.spp, a.threads, w, seeds, tmp):
                            imgs.append({**x, "spp": a.spp})
                    A, B = imgs
                    if a.save:
                        a.save.mkdir(parents=True, exist_ok=True)
                        np.save(a.save / f"{c}_{rep}_A.npy", A["y"])
                        np.save(a.save / f"{c}_{rep}_B.npy", B["y"])
                    spp = A["spp"]
                    ih, iw = A["y"].shape  # the image's (a TOML scene's film is not parsed)
                    masks = regions(A["y"].shape, 0.5 * (A["y"] + B["y"]))
                    rv = {k: rel_var(A["y"], B["y"], spp, m) for k, m in masks.items()}
                    secs = 0.5 * (A["seconds"] + B["seconds"])
                    rate = iw * ih * spp / secs
                    results[c].append({"rel_var": rv, "seconds": secs, "samples_per_s": rate,
                                       "spp": spp, "load": loadavg(), "size": [iw, ih]})
                    log(f"{c} repeat {rep}: {rv} {rate / 1e6:.3f} M samples/s")
        finally:
            if mts is not None:
                mts.close()
                (scene.parent / f".{scene.stem}.ldsampler.xml").unlink(missing_ok=True)

    names = ["whole image", "floor", "typical floor pixel"]
    if results and any(results.values()):
        first = next(r for r in results.values() if r)
        w, h = first[0]["size"]
    print(f"# Variance per sample: {scene.relative_to(ROOT)}, {w}×{h}, {a.spp} spp, "
          f"{a.threads} threads, {a.repeats} repeat(s)")
    print(f"{datetime.date.today()}, {cpu_model()}, {platform.python_version()}, spectrace "
          f"{be.git_head()}" + (f", Blender {cycles_version()}" if "cycles" in configs else ""))
    print()
    print("| renderer | " + " | ".join(f"rel. var. {n}" for n in names)
          + " | M samples/s | efficiency (1/s) |")
    print("| --- |" + " ---: |" * (len(names) + 2))
    summary = {}
    for c in configs:
        rs = results[c]
        rv = {n: float(np.mean([r["rel_var"][n] for r in rs])) for n in names}
        rate = float(np.median([r["samples_per_s"] for r in rs]))
        eff = rate / rv["whole image"]
        summary[c] = {"rel_var": rv, "samples_per_s": rate, "efficiency": eff, "runs": rs}
        label = {"mitsuba": f"Mitsuba 3 scalar_spectral + {a.mitsuba_sampler}"}.get(c, c)
        print(f"| {label} | " + " | ".join(f"{rv[n]:.4g}" for n in names)
              + f" | {rate / 1e6:.3f} | {eff:.4g} |")
    for s in skipped:
        print(f"\nskipped: {s}")
    OUT_JSON.parent.mkdir(parents=True, exist_ok=True)
    OUT_JSON.write_text(json.dumps(summary, indent=1, default=lambda o: None))
    return 1 if skipped else 0


if __name__ == "__main__":
    sys.exit(main())
