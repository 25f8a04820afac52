#!/usr/bin/env python3
"""Renders the Mitsuba 3 reference images for the spectrace-vs-Mitsuba comparison.

Usage:

    pip install mitsuba==3.9.1 OpenImageIO && python3 scripts/gen_references.py [--spp N] [scene ...]

For every scene `tests/reference/<name>/scene.xml` (all of them when no names are given) this
renders TWO independent references with Mitsuba 3.9.1 in the `scalar_spectral` variant, with
different seeds (`mi.render(scene, seed=…, spp=…)`), and writes

    tests/reference/<name>/ref_a.exr   float32 EXR, channels X, Y, Z (Mitsuba's XYZ film)
    tests/reference/<name>/ref_b.exr   the same with the other seed
    tests/reference/<name>/noise.txt   the measured noise between the two (see below)

Mitsuba's XYZ film is XYZ / ∫ȳ for the numbers in the file taken as W·m⁻²·sr⁻¹·nm⁻¹; spectrace
writes the same scale with `--mitsuba-units` (which divides its absolute X, Y, Z by
K_m·∫ȳ = 683.002 × 106.856895 = 72 983.0; ../shared/PHYSICS.md, "Comparing with Mitsuba 3").

noise.txt holds `key = value` lines. Over all pixels, with Y the luminance channel and
eps = EPS_REL × mean Y (so that black pixels count as agreeing, independent of the image's
absolute scale):

    mean_y            mean Y of (ref_a + ref_b) / 2
    rms_diff_y        sqrt(mean((a − b)²)) in Y
    mean_rel_diff_y   mean |a − b| / (|a + b|/2 + eps) in Y
    mean_rel_diff_xyz the same averaged over X, Y and Z

A comparison of a single image with ref_a at the same spp should therefore show a mean
relative difference close to mean_rel_diff_y (two images with the same noise); at fewer spp
the expected difference grows roughly like sqrt((1/spp + 1/spp_ref) / (2/spp_ref)).

The sample counts per scene (SPP below) are chosen so that one reference takes about 30–60 s
on two cores (measured on an otherwise idle 2-core machine); --spp overrides them for all scenes (e.g. --spp 64 for a quick test).
The seeds are fixed (SEED_A, SEED_B), so the output is reproducible for a given Mitsuba build.
"""

import argparse
import os
import sys
import time

import numpy as np

import mitsuba as mi

MITSUBA_VERSION = "3.9.1"
VARIANT = "scalar_spectral"
SEED_A = 1
SEED_B = 2
EPS_REL = 1e-2

# Sample counts per scene (96 × 96 pixels): ≲ 60 s per reference on 2 cores.
SPP = {
    "blackbody": 6144,
    "conductor_presets": 8192,
    "constant_env": 8192,
    "defaults": 8192,
    "cornell": 3072,
    "dielectric_sphere": 8192,
    "directional": 8192,
    "gold_copper": 8192,
    "point_plane": 8192,
    "rough_beckmann": 8192,
    "rough_conductor": 8192,
    "rough_dielectric": 6144,
    "spot": 8192,
    # 48 × 48 one-difference scenes (issue 8)
    "gaussian_edge": 32768,
    "tent_edge": 32768,
    "smooth_mesh": 8192,
    "spot_ramp": 8192,
    # issue 10
    "textures": 4096,
    "envmap": 4096,
    "plastics": 4096,
    "serialized": 4096,
    "direct": 4096,
    "orthographic": 4096,
    "mask": 4096,
    "cylinders": 4096,
    "anisotropic": 4096,
    "blend": 4096,
    "bumps": 4096,
    "instances": 4096,
    "textured_lobes": 4096,
    "emissive_textures": 4096,
    "projector": 4096,
    "spot_texture": 4096,
}
DEFAULT_SPP = 1024

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REF_DIR = os.path.join(ROOT, "tests", "reference")


def write_exr(path, img, meta):
    """float32 EXR with channels named X, Y, Z."""
    import OpenImageIO as oiio

    h, w, c = img.shape
    assert c == 3, f"expected 3 channels (X, Y, Z), got {c}"
    spec = oiio.ImageSpec(w, h, 3, oiio.FLOAT)
    spec.channelnames = ("X", "Y", "Z")
    spec.attribute("compression", "zip")
    for k, v in meta.items():
        spec.attribute(k, str(v))
    out = oiio.ImageOutput.create(path)
    if out is None or not out.open(path, spec):
        raise RuntimeError(f"cannot write {path}: {oiio.geterror()}")
    out.write_image(np.ascontiguousarray(img, dtype=np.float32))
    out.close()


def read_exr_xyz(path):
    import OpenImageIO as oiio

    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError(f"cannot read {path}: {oiio.geterror()}")
    names = list(inp.spec().channelnames)
    px = inp.read_image(oiio.FLOAT)
    inp.close()
    return np.stack([px[..., names.index(c)] for c in ("X", "Y", "Z")], axis=-1)


def stats(a, b):
    """Noise statistics between two XYZ images of the same scene."""
    mean_y = float((a[..., 1] + b[..., 1]).mean() / 2)
    eps = EPS_REL * abs(mean_y) if mean_y != 0 else 1e-12
    d = a - b
    rel = np.abs(d) / (np.abs(a + b) / 2 + eps)
    return {
        "mean_y_a": float(a[..., 1].mean()),
        "mean_y_b": float(b[..., 1].mean()),
        "mean_y": mean_y,
        "rms_diff_y": float(np.sqrt((d[..., 1] ** 2).mean())),
        "rel_rms_diff_y": float(np.sqrt((d[..., 1] ** 2).mean()) / mean_y) if mean_y else 0.0,
        "mean_rel_diff_y": float(rel[..., 1].mean()),
        "mean_rel_diff_xyz": float(rel.mean()),
        "max_abs_diff_y": float(np.abs(d[..., 1]).max()),
        "eps": eps,
    }


def render(scene_path, seed, spp):
    scene = mi.load_file(scene_path)
    film = scene.sensors()[0].film()
    t = time.time()
    img = np.array(mi.render(scene, seed=seed, spp=spp), dtype=np.float32)
    dt = time.time() - t
    fmt = str(film.bitmap().pixel_format())
    if img.ndim != 3 or img.shape[2] != 3:
        raise RuntimeError(f"{scene_path}: expected an H×W×3 XYZ image, got {img.shape}")
    if "XYZ" not in fmt:
        raise RuntimeError(f"{scene_path}: the film's pixel format is {fmt}, expected XYZ")
    if not np.all(np.isfinite(img)):
        raise RuntimeError(f"{scene_path}: non-finite pixels")
    return img, dt


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, help="samples per pixel for every scene (default: per scene)")
    ap.add_argument("scenes", nargs="*", help="scene names (default: all in tests/reference/)")
    args = ap.parse_args()

    assert mi.__version__ == MITSUBA_VERSION, f"need mitsuba {MITSUBA_VERSION}, found {mi.__version__}"
    mi.set_variant(VARIANT)

    names = args.scenes or sorted(
        d for d in os.listdir(REF_DIR) if os.path.isfile(os.path.join(REF_DIR, d, "scene.xml"))
    )
    for name in names:
        d = os.path.join(REF_DIR, name)
        path = os.path.join(d, "scene.xml")
        if not os.path.isfile(path):
            sys.exit(f"no such scene: {path}")
        spp = args.spp or SPP.get(name, DEFAULT_SPP)
        imgs, times = [], []
        for tag, seed in (("a", SEED_A), ("b", SEED_B)):
            img, dt = render(path, seed, spp)
            meta = {
                "spectrace:scene": f"tests/reference/{name}/scene.xml",
                "spectrace:renderer": f"mitsuba {mi.__version__} {VARIANT}",
                "spectrace:spp": spp,
                "spectrace:seed": seed,
                "spectrace:units": "Mitsuba XYZ film: XYZ / integral(ybar); spectrace --mitsuba-units",
            }
            write_exr(os.path.join(d, f"ref_{tag}.exr"), img, meta)
            # read back to make sure the file holds what the harness will see
            back = read_exr_xyz(os.path.join(d, f"ref_{tag}.exr"))
            assert np.array_equal(back, img), "EXR round trip changed the pixels"
            imgs.append(img)
            times.append(dt)
            print(f"{name}: ref_{tag} seed {seed}, {spp} spp, {dt:.1f} s, mean Y {img[..., 1].mean():.6g}", flush=True)
        s = stats(*imgs)
        lines = [
            f"# Noise between two Mitsuba {mi.__version__} {VARIANT} references of tests/reference/{name}/scene.xml",
            "# (written by scripts/gen_references.py; eps = %g × mean_y)" % EPS_REL,
            f"scene = {name}",
            f"mitsuba = {mi.__version__}",
            f"variant = {VARIANT}",
            f"spp = {spp}",
            f"seed_a = {SEED_A}",
            f"seed_b = {SEED_B}",
            f"width = {imgs[0].shape[1]}",
            f"height = {imgs[0].shape[0]}",
        ]
        lines += [f"{k} = {v:.6g}" for k, v in s.items()]
        lines += [f"seconds_a = {times[0]:.1f}", f"seconds_b = {times[1]:.1f}"]
        with open(os.path.join(d, "noise.txt"), "w") as f:
            f.write("\n".join(lines) + "\n")
        print(f"{name}: mean Y {s['mean_y']:.6g}, rms(a-b) {s['rms_diff_y']:.3g}, "
              f"mean rel diff {s['mean_rel_diff_y']:.4f}", flush=True)


if __name__ == "__main__":
    main()
