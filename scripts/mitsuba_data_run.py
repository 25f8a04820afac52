#!/usr/bin/env python3
"""Renders every scene of Mitsuba 3's public data repository with spectrace and reports which
render (issue 31's census).

The set (141 files at mitsuba-data 01100fa): the 41 test scenes with official references
(`tests/scenes/*/test_*.xml` and `tests/scenes/infinite_mirrors/scene_path.xml`), the documentation
scenes (`docs/scenes/*.xml`, not their `include/` fragments), the three Cornell boxes
(`scenes/cbox/cbox*.xml`) and `scenes/matpreview/matpreview.xml`.

Each scene is copied (the whole snapshot, so that relative paths resolve) into a temporary folder
where its film is capped at `--max-px` pixels along its longer side (width and height integers and
the `resx`/`resy`/`res` defaults are scaled together, keeping the aspect), then rendered with
`spectrace render --mitsuba-units --spp 16`. A scene "renders" when spectrace exits 0 and writes
an EXR; otherwise the first error line is printed.

Usage:
    cargo build --release
    python3 scripts/mitsuba_data_run.py [--data DIR] [--max-px 256] [--spp 16] [--jobs 1]
        [--filter SUBSTRING,...] [--out-dir DIR]

`--data` is a checkout of https://github.com/mitsuba-renderer/mitsuba-data (the default is the
mirror `/work/.mirror/mitsuba-renderer+mitsuba-data/repo`, a bare git directory read with
`git archive`). Standard library only.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MIRROR = "/work/.mirror/mitsuba-renderer+mitsuba-data/repo"
SPECTRACE = os.path.join(ROOT, "target", "release", "spectrace")


def extract(data, dest):
    """Copies the data snapshot into dest (git archive for a bare mirror, copytree otherwise)."""
    if os.path.isdir(os.path.join(data, "docs")):
        shutil.copytree(data, dest, dirs_exist_ok=True)
        return
    # The mirror lacks some large blobs, so `git archive` fails: read the blobs one by one
    # through `git cat-file --batch` and skip the missing ones (their scenes fail to load).
    tree = subprocess.run(["git", "-C", data, "ls-tree", "-r", "HEAD"], check=True,
                          capture_output=True, text=True).stdout.splitlines()
    entries = [(line.split()[2], line.split("\t", 1)[1]) for line in tree
               if line.split()[1] == "blob"]
    batch = subprocess.run(["git", "-C", data, "cat-file", "--batch"], check=True,
                           capture_output=True,
                           input="".join(sha + "\n" for sha, _ in entries).encode()).stdout
    at = 0
    for _, path in entries:
        end = batch.index(b"\n", at)
        header = batch[at:end].split()
        at = end + 1
        if header[-1] == b"missing":
            continue
        size = int(header[2])
        target = os.path.join(dest, path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as f:
            f.write(batch[at:at + size])
        at += size + 1


def scene_list(root):
    scenes = []
    tests = os.path.join(root, "tests", "scenes")
    for case in sorted(os.listdir(tests)):
        folder = os.path.join(tests, case)
        for name in sorted(os.listdir(folder)):
            if name.endswith(".xml") and (name.startswith("test_") or name == "scene_path.xml"):
                scenes.append(os.path.join("tests", "scenes", case, name))
    docs = os.path.join(root, "docs", "scenes")
    scenes += [os.path.join("docs", "scenes", n) for n in sorted(os.listdir(docs))
               if n.endswith(".xml")]
    scenes += [os.path.join("scenes", "cbox", n)
               for n in sorted(os.listdir(os.path.join(root, "scenes", "cbox")))
               if n.startswith("cbox") and n.endswith(".xml")]
    scenes.append(os.path.join("scenes", "matpreview", "matpreview.xml"))
    return scenes


INT_RE = re.compile(r'(<integer\s+name="(width|height)"\s+value=")(\d+)(")')
DEF_RE = re.compile(r'(<default\s+name="(resx|resy|res|width|height)"\s+value=")(\d+)(")')


def cap_film(path, max_px):
    """Scales a file's numeric film sizes so that the larger is at most max_px."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    sizes = [int(m.group(3)) for m in INT_RE.finditer(text)]
    sizes += [int(m.group(3)) for m in DEF_RE.finditer(text)]
    if not sizes or max(sizes) <= max_px:
        return
    scale = max_px / max(sizes)

    def sub(m):
        return f"{m.group(1)}{max(1, round(int(m.group(3)) * scale))}{m.group(4)}"

    text = DEF_RE.sub(sub, INT_RE.sub(sub, text))
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def official_ref(work, scene):
    """Mitsuba's official spectral reference of a test scene and its per-sample variance (the
    scene's name less its integrator suffix, in `refs/`), or None."""
    if not scene.startswith(os.path.join("tests", "scenes")):
        return None
    folder, name = os.path.split(scene)
    base = os.path.join(work, folder, "refs", name[:-4].rsplit("_", 1)[0] + "_ref_spectral")
    if os.path.exists(base + ".exr") and os.path.exists(base + "_var.exr"):
        return base + ".exr", base + "_var.exr"
    return None


def read_rgb(path):
    import numpy as np
    import OpenImageIO as oiio

    i = oiio.ImageInput.open(path)
    spec = i.spec()
    px = i.read_image(0, 0, 0, spec.nchannels, "float")
    i.close()
    names = list(spec.channelnames)
    return np.stack([px[:, :, names.index(c)] for c in "RGB"], axis=-1).astype(np.float64)


def compare(work, scene, spp, out_dir):
    """Renders a test scene at its own resolution with seeds 1 and 2 and compares it with the
    official reference: per channel the mean ratio and its z-score (standard error from the
    seed pair), and the fraction of pixels passing Mitsuba's own per-pixel test
    (`src/render/tests/test_renders.py`: z = |ours − ref|·√(spp / max(var_ref, 10⁻⁴)), a pixel
    passes when its two-sided p-value exceeds the Šidák level 1 − 0.99^(1/pixels))."""
    import math

    import numpy as np

    ref_path, var_path = official_ref(work, scene)
    ref, var = read_rgb(ref_path), read_rgb(var_path)
    imgs = []
    for seed in (1, 2):
        exr = os.path.join(out_dir, scene.replace(os.sep, "__")[:-4] + f"_s{seed}.exr")
        run = subprocess.run([SPECTRACE, "render", os.path.join(work, scene), "--mitsuba-units",
                              "--spp", str(spp), "--seed", str(seed), "-q", "-o", exr, "--png",
                              exr[:-4] + ".png"], capture_output=True, text=True)
        if run.returncode != 0:
            return f"render failed: {first_error(run.stderr)}"
        imgs.append(read_rgb(exr))
    if imgs[0].shape != ref.shape:
        return f"size {imgs[0].shape} differs from the reference's {ref.shape}"
    ours = (imgs[0] + imgs[1]) / 2
    n = ours[:, :, 0].size
    parts = []
    for c, name in enumerate("RGB"):
        se = (imgs[0][:, :, c] - imgs[1][:, :, c]).std() / 2 / math.sqrt(n)
        m, r = ours[:, :, c].mean(), ref[:, :, c].mean()
        z = (m - r) / se if se > 0 else float("nan")
        parts.append(f"{name} {m / r if r else float('nan'):.4f} (z {z:+.1f})")
    z = np.abs(ours - ref) * np.sqrt(2 * spp / np.maximum(var, 1e-4))
    p = np.vectorize(lambda x: math.erfc(x / math.sqrt(2)))(z)
    level = 1 - 0.99 ** (1 / n)
    passing = (p > level).mean()
    return "  ".join(parts) + f"  pixels passing {100 * passing:.2f} %"


MITSUBA_SCRIPT = r"""
import sys, numpy as np, mitsuba as mi
mi.set_variant(sys.argv[1])
scene = mi.load_file(sys.argv[2])
spp = int(sys.argv[3])
for seed, out in ((0, sys.argv[4]), (1, sys.argv[5])):
    img = mi.render(scene, spp=spp, seed=seed)
    bmp = mi.Bitmap(img, channel_names=["R", "G", "B"] + scene.integrator().aov_names())
    bmp.write(out)
"""


def block_compare(work, scene, spp, out_dir, variant):
    """Renders a scene (film capped) with Mitsuba (two seeds, `variant`) and spectrace (two
    seeds) at `spp` and compares 8 × 8-pixel blocks of each renderer's two-seed mean: a block
    is off when its spectrace−Mitsuba difference in any channel exceeds 4 standard errors
    (from the four seeds' differences, pooled over the image for blocks as noisy as it) plus
    0.5 % of the block's value. Prints the image mean ratios and the fraction of blocks off."""
    import numpy as np

    stem = os.path.join(out_dir, scene.replace(os.sep, "__")[:-4])
    mi = [stem + "_mi0.exr", stem + "_mi1.exr"]
    env = dict(os.environ)
    env.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1")
    run = subprocess.run([sys.executable, "-c", MITSUBA_SCRIPT, variant, os.path.join(work, scene),
                          str(spp), *mi], capture_output=True, text=True, env=env)
    if run.returncode != 0:
        return "mitsuba failed: " + (run.stderr.strip().splitlines() or ["?"])[-1][:160]
    ours = []
    for seed in (1, 2):
        exr = stem + f"_st{seed}.exr"
        r = subprocess.run([SPECTRACE, "render", os.path.join(work, scene), "--mitsuba-units",
                            "--spp", str(spp), "--seed", str(seed), "-q", "-o", exr, "--png",
                            exr[:-4] + ".png"], capture_output=True, text=True)
        if r.returncode != 0:
            return f"spectrace failed: {first_error(r.stderr)}"
        ours.append(read_rgb(exr))
    theirs = [read_rgb(m) for m in mi]
    if ours[0].shape != theirs[0].shape:
        return f"size {ours[0].shape} differs from Mitsuba's {theirs[0].shape}"
    h, w, _ = ours[0].shape
    bh, bw = h // 8, w // 8

    def blocks(img):
        return img[:bh * 8, :bw * 8].reshape(bh, 8, bw, 8, 3).mean(axis=(1, 3))

    s1, s2, m1, m2 = (blocks(x) for x in (*ours, *theirs))
    s, m = (s1 + s2) / 2, (m1 + m2) / 2
    # per block variance of (s − m) from the seed pairs: ((s1−s2)² + (m1−m2)²)/4, pooled with
    # the image's median so that a block's single-sample estimate does not decide alone
    var = ((s1 - s2) ** 2 + (m1 - m2) ** 2) / 4
    var = np.maximum(var, np.median(var, axis=(0, 1)))
    off = np.abs(s - m) > 4 * np.sqrt(var) + 0.005 * np.abs(m) + 1e-6
    off_blocks = off.any(axis=2).mean()
    ratio = [ours[0][..., c].mean() / 2 + ours[1][..., c].mean() / 2 for c in range(3)]
    ref = [theirs[0][..., c].mean() / 2 + theirs[1][..., c].mean() / 2 for c in range(3)]
    parts = [f"{n} {a / b if b else float('nan'):.4f}" for n, a, b in zip("RGB", ratio, ref)]
    return "  ".join(parts) + f"  blocks off {100 * off_blocks:.1f} % of {bh * bw}"


def first_error(stderr):
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    for line in lines:
        if "error" in line.lower():
            return line[:200]
    return (lines[0] if lines else "no output")[:200]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=MIRROR)
    ap.add_argument("--max-px", type=int, default=256)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--filter", default="", help="comma-separated substrings of scene paths")
    ap.add_argument("--out-dir", default="", help="keep the EXRs here (default: discarded)")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per scene")
    ap.add_argument("--mitsuba-spp", type=int, default=0,
                    help="instead of the census, render every selected scene (film capped) with "
                         "Mitsuba 3 and spectrace at this many spp (×2 seeds each) and compare "
                         "8 × 8-pixel blocks")
    ap.add_argument("--variant", default="llvm_ad_spectral",
                    help="Mitsuba variant for --mitsuba-spp (scalar_spectral needs no LLVM)")
    ap.add_argument("--compare-spp", type=int, default=0,
                    help="instead of the census, compare the test scenes that have official "
                         "references with them at this many spp (×2 seeds; needs numpy and "
                         "OpenImageIO)")
    args = ap.parse_args()
    if not os.path.exists(SPECTRACE):
        sys.exit(f"{SPECTRACE} is missing: run `cargo build --release` first")
    work = tempfile.mkdtemp(prefix="spectrace-mitsuba-data-")
    try:
        extract(args.data, work)
        wanted = args.filter.split(",")
        scenes = [s for s in scene_list(work) if any(w in s for w in wanted)]
        out_dir = args.out_dir or os.path.join(work, "_out")
        os.makedirs(out_dir, exist_ok=True)
        if args.compare_spp:
            for scene in scenes:
                if official_ref(work, scene):
                    print(f"{scene}: {compare(work, scene, args.compare_spp, out_dir)}",
                          flush=True)
            return
        for dirpath, _, files in os.walk(work):
            for name in files:
                if name.endswith(".xml"):
                    cap_film(os.path.join(dirpath, name), args.max_px)
        if args.mitsuba_spp:
            for scene in scenes:
                print(f"{scene}: {block_compare(work, scene, args.mitsuba_spp, out_dir, args.variant)}",
                      flush=True)
            return
        ok = 0
        failures = []
        for scene in scenes:
            exr = os.path.join(out_dir, scene.replace(os.sep, "__")[:-4] + ".exr")
            cmd = [SPECTRACE, "render", os.path.join(work, scene), "--mitsuba-units",
                   "--spp", str(args.spp), "-q", "-o", exr, "--png", exr[:-4] + ".png"]
            t0 = time.time()
            try:
                run = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
                code, err = run.returncode, run.stderr
            except subprocess.TimeoutExpired:
                code, err = -1, f"timed out after {args.timeout:.0f} s"
            secs = time.time() - t0
            if code == 0 and os.path.exists(exr):
                ok += 1
                print(f"ok    {secs:6.1f} s  {scene}", flush=True)
            else:
                failures.append((scene, first_error(err)))
                print(f"FAIL  {secs:6.1f} s  {scene}: {first_error(err)}", flush=True)
        print(f"\n{ok} of {len(scenes)} render")
        for scene, why in failures:
            print(f"  {scene}: {why}")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
