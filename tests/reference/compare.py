#!/usr/bin/env python3
"""Compares spectrace with the Mitsuba references in tests/reference/ (a diagnostic, not a test).

    cargo build --release && python3 tests/reference/compare.py [--spp 64] [scene ...]

For each scene: renders spectrace twice (--mitsuba-units, seeds 1 and 2) and Mitsuba 3.9.1
once at the same spp (seed 101, as the noise baseline at that spp), and prints

- Y ratio: mean Y of spectrace (both seeds) / mean Y of the references (ref_a, ref_b); the same
  for X and Z;
- rel(st, a): mean over pixels of |st − ref_a| / (|st + ref_a|/2 + eps) in Y, eps from noise.txt;
- rel(mi, a): the same for the Mitsuba render at the same spp (what agreement looks like at
  this spp), and rel(a, b) from noise.txt (the references' own noise);
- z(mean): (mean Y spectrace − mean Y refs) / its standard error, the standard errors estimated
  from seed-pair differences (st1 − st2, a − b);
- tiles: the image cut into 8 × 8 tiles of 12 × 12 pixels; the worst tile z-score and how many
  tiles have |z| > 4 (with 64 tiles, |z| > 4 should not happen by chance unless the noise is
  very heavy-tailed), and the Y ratio of the worst tile.

--cie-norm multiplies spectrace's images by 106.856895 / 106.7502594 = 1.0010002 first: Mitsuba
3.9.1 divides its film's XYZ by 106.7502594 (MI_CIE_Y_NORMALIZATION), not by the integral of its
own ȳ (106.857), so a unit flat spectrum reads Y = 1.0010 in Mitsuba; `--mitsuba-units` divides
by 683.002 × 106.856895 and so comes out 0.1 % below Mitsuba for every scene.
"""

import argparse
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BIN = os.path.join(ROOT, "target", "release", "spectrace")
TMP = os.environ.get("TMPDIR", "/tmp")
CIE_NORM = 106.856895 / 106.7502593994140625


def read_xyz(path):
    import OpenImageIO as oiio

    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError(oiio.geterror())
    names = list(inp.spec().channelnames)
    px = inp.read_image(oiio.FLOAT)
    inp.close()
    return np.stack([px[..., names.index(c)] for c in ("X", "Y", "Z")], axis=-1).astype(np.float64)


def noise(name):
    out = {}
    with open(os.path.join(HERE, name, "noise.txt")) as f:
        for line in f:
            if "=" in line and not line.startswith("#"):
                k, v = (s.strip() for s in line.split("=", 1))
                try:
                    out[k] = float(v)
                except ValueError:
                    out[k] = v
    return out


def rel(a, b, eps):
    return float((np.abs(a - b) / (np.abs(a + b) / 2 + eps)).mean())


def tiles(x, t=12):
    h, w = x.shape
    return x[: h // t * t, : w // t * t].reshape(h // t, t, w // t, t).mean(axis=(1, 3))


def spectrace(scene, spp, seed, out):
    subprocess.run(
        [BIN, "render", scene, "--spp", str(spp), "--seed", str(seed), "--mitsuba-units", "-o", out,
         "--png", out.replace(".exr", ".png"), "--quiet"],
        check=True,
    )
    return read_xyz(out)


def mitsuba(scene, spp, seed):
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    return np.array(mi.render(mi.load_file(scene), seed=seed, spp=spp), dtype=np.float64)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--cie-norm", action="store_true", help="scale spectrace by 1.0010002 (see above)")
    ap.add_argument("--reuse", action="store_true", help="reuse spectrace/Mitsuba renders from a previous run")
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    names = args.scenes or sorted(
        d for d in os.listdir(HERE) if os.path.isfile(os.path.join(HERE, d, "ref_a.exr"))
    )
    hdr = (f"{'scene':18} {'Y ratio':>8} {'X ratio':>8} {'Z ratio':>8} {'rel(st,a)':>9} {'rel(mi,a)':>9} "
           f"{'rel(a,b)':>8} {'z(mean)':>8} {'worst tile z':>12} {'|z|>4':>5} {'tile ratio':>10}")
    print(hdr)
    rows = []
    for name in names:
        scene = os.path.join(HERE, name, "scene.xml")
        nz = noise(name)
        eps = nz["eps"]
        a = read_xyz(os.path.join(HERE, name, "ref_a.exr"))
        b = read_xyz(os.path.join(HERE, name, "ref_b.exr"))
        f1, f2 = (os.path.join(TMP, f"st_{name}_{args.spp}_{i}.exr") for i in (1, 2))
        fm = os.path.join(TMP, f"mi_{name}_{args.spp}.npy")
        if args.reuse and all(os.path.exists(f) for f in (f1, f2, fm)):
            s1, s2, m = read_xyz(f1), read_xyz(f2), np.load(fm)
        else:
            s1 = spectrace(scene, args.spp, 1, f1)
            s2 = spectrace(scene, args.spp, 2, f2)
            m = mitsuba(scene, args.spp, 101)
            np.save(fm, m)
        if args.cie_norm:
            s1, s2 = s1 * CIE_NORM, s2 * CIE_NORM
        st, ref = (s1 + s2) / 2, (a + b) / 2
        ratio = [st[..., c].mean() / ref[..., c].mean() for c in range(3)]
        n = st.shape[0] * st.shape[1]
        var_mean = (((s1 - s2) ** 2).sum(axis=(0, 1)) / 4 + ((a - b) ** 2).sum(axis=(0, 1)) / 4) / n**2
        z_xyz = (st.mean(axis=(0, 1)) - ref.mean(axis=(0, 1))) / np.sqrt(var_mean)
        z_mean = z_xyz[1]
        tv = (tiles((s1 - s2)[..., 1] ** 2) + tiles((a - b)[..., 1] ** 2)) / 4 / 144
        td = tiles(st[..., 1]) - tiles(ref[..., 1])
        tz = td / np.sqrt(np.maximum(tv, 1e-30))
        big = np.abs(tiles(ref[..., 1])) > 0.01 * abs(ref[..., 1].mean())
        tz = np.where(big, tz, 0.0)
        wi = np.unravel_index(np.argmax(np.abs(tz)), tz.shape)
        tr = tiles(st[..., 1])[wi] / tiles(ref[..., 1])[wi]
        r = dict(
            name=name, y=ratio[1], x=ratio[0], zz=ratio[2],
            rel_st=rel(s1[..., 1], a[..., 1], eps), rel_mi=rel(m[..., 1], a[..., 1], eps),
            rel_ab=nz["mean_rel_diff_y"], z=z_mean, tz=tz[wi], nbig=int((np.abs(tz) > 4).sum()),
            tr=tr, tile=(int(wi[0]), int(wi[1])), zx=z_xyz[0], zz_=z_xyz[2], mean_st=st[..., 1].mean(), mean_ref=ref[..., 1].mean(),
        )
        rows.append(r)
        print(f"{name:18} {r['y']:8.4f} {r['x']:8.4f} {r['zz']:8.4f} {r['rel_st']:9.4f} {r['rel_mi']:9.4f} "
              f"{r['rel_ab']:8.4f} {r['z']:8.1f} {r['tz']:12.1f} {r['nbig']:5d} {r['tr']:10.3f}  tile(row,col)={r['tile']}  z(X,Z mean)=({r['zx']:.1f}, {r['zz_']:.1f})",
              flush=True)
    return rows


if __name__ == "__main__":
    sys.exit(0 if main() is not None else 1)
