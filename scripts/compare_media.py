#!/usr/bin/env python3
"""Compares spectrace with Mitsuba 3's official references for its participating-media test
scenes (a diagnostic, not a test; the test is tests/media_reference.rs).

    cargo build --release
    python3 scripts/compare_media.py --data /path/to/mitsuba-data [--spp 256] [scene ...]

mitsuba-data is the public repository mitsuba-renderer/mitsuba-data; its
tests/scenes/participating_media/refs/*_ref_spectral.exr are Mitsuba's spectral renders in
linear sRGB. For each scene spectrace renders twice (seeds 1 and 2, --mitsuba-units, linear
sRGB R, G, B) and this prints, per channel, the mean ratio spectrace / reference with its
z-score (the standard error from the seed-pair difference) and the mean relative absolute
difference per pixel, next to the same for the two spectrace seeds (what noise alone gives).
"""

import argparse
import os
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "target", "release", "spectrace")
SCENES = [
    "test_homo_area_light_volpath",
    "test_homo_dielectric_envmap_volpath",
    "test_homo_emitter_inside_medium_volpath",
    "test_homo_null_envmap_volpath",
    "test_homo_obj_inside_medium_volpath",
    "test_homo_roughdielectric_spot_volpath",
    "test_homo_spectral_sigmat_volpathmis",
    "test_surf_area_light_volpath",
    "test_hetero_sigmat_albedo_volpath",
    "test_hetero_sigmat_volpath",
    "test_hetero_spectral_sigmat_no_scattering_volpath",
    "test_hetero_spectral_sigmat_volpathmis",
]


def read_rgb(path):
    i = oiio.ImageInput.open(path)
    s = i.spec()
    px = i.read_image(0, 0, 0, s.nchannels, "float")
    i.close()
    names = list(s.channelnames)
    return np.stack([px[:, :, names.index(c)] for c in "RGB"], axis=-1).astype(np.float64)


def ref_name(scene):
    base = scene.rsplit("_", 1)[0]
    return base + "_ref_spectral.exr"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True)
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    folder = os.path.join(a.data, "tests", "scenes", "participating_media")
    for scene in a.scenes or SCENES:
        xml = os.path.join(folder, scene + ".xml")
        ref = read_rgb(os.path.join(folder, "refs", ref_name(scene)))
        imgs = []
        for seed in (1, 2):
            out = f"/tmp/cmpmedia_{scene}_{seed}.exr"
            r = subprocess.run(
                [BIN, "render", xml, "--spp", str(a.spp), "--seed", str(seed),
                 "--mitsuba-units", "-o", out, "--png", out + ".png"],
                capture_output=True, text=True)
            if r.returncode != 0:
                print(f"{scene}: spectrace failed: {r.stderr.strip().splitlines()[-1:]}")
                break
            imgs.append(read_rgb(out))
        if len(imgs) < 2:
            continue
        st = (imgs[0] + imgs[1]) / 2
        n = st[:, :, 0].size
        eps = 1e-3 * max(ref.mean(), 1e-6)
        print(f"{scene} ({a.spp} spp × 2)")
        for c, name in enumerate("RGB"):
            m_st, m_ref = st[:, :, c].mean(), ref[:, :, c].mean()
            se = (imgs[0][:, :, c] - imgs[1][:, :, c]).std() / 2 / np.sqrt(n)
            rel = np.mean(np.abs(st[:, :, c] - ref[:, :, c]) / (np.abs(st[:, :, c] + ref[:, :, c]) / 2 + eps))
            rel_noise = np.mean(np.abs(imgs[0][:, :, c] - imgs[1][:, :, c])
                                / (np.abs(imgs[0][:, :, c] + imgs[1][:, :, c]) / 2 + eps)) / np.sqrt(2)
            z = (m_st - m_ref) / se if se > 0 else float("nan")
            print(f"  {name}: ratio {m_st / m_ref:.4f}  z {z:+.1f}  rel {rel:.4f} (noise ~{rel_noise:.4f})")


if __name__ == "__main__":
    sys.exit(main())
