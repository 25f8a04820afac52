#!/usr/bin/env python3
"""Benchmark spectrace's BVH against Embree 4 (through embreex) on the same rays and triangles.

How to run (from the repository root):

    pip install -r scripts/bench-requirements.txt      # numpy, embreex (Embree 4.4)
    python3 scripts/gen_heightfield.py                  # only if benchmarks/scenes/heightfield.ply is missing
    python3 scripts/bench_embree.py                     # 1024x1024 rays, 5 repetitions

Options: --size N (image side: N*N camera rays, default 1024), --reps R (default 5), --scene FILE
(default benchmarks/scenes/heightfield.xml; meshes only), --out DIR (default target/bench),
--robust (Embree's RTC_SCENE_FLAG_ROBUST), --skip-rust (reuse the files and numbers of the last
run in OUT: the spectrace column then reads OUT/spectrace_results.txt). The script honours
CARGO_TARGET_DIR. Extra `cargo` flags, e.g. for `-C target-cpu=native`, go through RUSTFLAGS as
usual.

What it does:
  * Runs `cargo run --release --example bench_rays -- --size N --reps R --out OUT` (see
    examples/bench_rays.rs). The example loads the scene as the renderer does, writes the
    triangles its BVH indexes (world space, after to_world; the height field and the area
    light's rectangle: 1,002,530 triangles) and two ray batches, times closest-hit and
    occlusion queries on each, single-threaded, and prints Mrays/s and checksums.
      - camera: one ray per pixel centre of an N×N image from the scene's camera;
      - diffuse: from each camera ray's closest hit, a cosine-distributed direction about the
        geometric normal (facing the camera ray's side; hash-based random numbers), origin
        offset along the normal by the hit's error bound as the renderer spawns bounces.
      - closest: t_max = ∞. occluded: the same rays with t_max = 0.999 × the ray's own closest
        hit distance (from spectrace), or, for a ray that misses, the distance at which it leaves
        the scene's bounding sphere. So every occlusion ray is unoccluded by construction: the
        worst case for an any-hit query (no early exit; a shadow ray toward a visible point), and
        its hit count should be ~0 on both sides.
  * Builds an Embree scene from the same triangle file (one TriangleMesh, indexed; Embree's
    default build quality, non-robust unless --robust), commits it with a small untimed warm-up
    query, then times `scene.run(origins, directions, dists=t_max, query='INTERSECT' |
    'OCCLUDED')` on each whole batch (one call per batch and repetition; best and median of R).
  * Prints one Markdown table, best-of-R rates (median in brackets), then the checksums and the
    per-ray agreement of the two libraries.

What is measured, and caveats:
  * Both sides are single-threaded. embreex 4.4's `run` is a Cython loop calling rtcIntersect1 /
    rtcOccluded1 one ray at a time (no packets, no streams, no threads); the script checks this
    by comparing CPU time with wall time of each timed call (ratio printed: 1.0 = one busy
    thread; below 1 the process was waiting for a core, i.e. other load on the machine disturbed
    that measurement; above 1 more than one thread ran). spectrace's example runs its queries in
    a plain loop on the main thread.
    Embree's BVH build uses TBB threads, but the build is not timed (nor is spectrace's).
  * Per-call overhead of embreex (argument checks, allocating the result arrays) is amortised
    over the whole batch (1M camera rays at the default size). The per-ray overhead of the
    Cython loop (copying the ray from the numpy arrays, filling RTCRayHit, writing results) is
    measured on a scene with a single far-away triangle, where Embree does almost nothing, and
    printed in ns/ray; the Embree column is NOT corrected for it (it is an upper bound of what
    Python costs Embree per ray). embreex reads origins, directions and `dists` through typed
    float32 buffers: it neither converts nor copies them (another dtype is an error, checked:
    "Buffer dtype mismatch"); the script makes them C-contiguous float32 before any timer starts.
    `dists` is written in place by embreex, so each timed call gets a fresh copy made before the
    timer starts.
  * tnear: embreex sets tnear = 0 for every ray and offers no per-ray tnear; tfar comes from
    `dists` per ray. spectrace's rays are (0, t_max) too, and the diffuse rays start off the
    surface (origin offset by the error bound), so the interval is the same up to whether t = 0
    or t = t_max counts.
  * What each query returns differs: spectrace's `intersect` builds the full Intersection (hit
    point with error bound, normals, uv) after traversal; embreex INTERSECT without output
    returns the primitive id (Embree computes t, u, v and Ng). Both occlusion queries return a
    flag. spectrace's triangle test is watertight with conservative error bounds; Embree's
    default (non-robust) test is not watertight, and --robust selects its robust mode.
  * ISA: the Embree wheel dispatches at run time to the widest kernels the CPU has (AVX2 on the
    project's machine; Embree uses 8-wide BVH nodes for triangles from AVX on); spectrace is
    compiled for the target's baseline (x86-64: SSE2) unless RUSTFLAGS says otherwise, and its
    BVH is 4-wide.
  * Agreement: per ray, hit/miss of closest-hit queries and the relative difference of the
    hit distances. A handful of rays can differ: rays through a shared edge or vertex (watertight
    vs not: Embree's default mode lets a few rays through cracks between adjacent triangles,
    which --robust closes) and, for diffuse rays, rays grazing the surface they leave.
  * The two libraries run one after the other, never at the same time. Run on an idle machine:
    on 2 cores, any other process (a cargo build) shows up in both columns.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
BATCHES = ("camera", "diffuse")
QUERIES = ("closest", "occluded")


def run_rust(args: argparse.Namespace, out: Path) -> dict:
    cmd = [
        "cargo", "run", "--release", "--example", "bench_rays", "--",
        "--scene", str(args.scene), "--size", str(args.size), "--reps", str(args.reps),
        "--out", str(out),
    ]
    print("$ " + " ".join(cmd), file=sys.stderr, flush=True)
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit(f"bench_rays failed (exit {p.returncode})")
    (out / "spectrace_results.txt").write_text(p.stdout)
    return parse_results(p.stdout)


def parse_results(text: str) -> dict:
    res = {}
    for line in text.splitlines():
        if not line.startswith("RESULT "):
            continue
        kv = dict(re.findall(r"(\w+)=(\S+)", line))
        res[(kv["batch"], kv["query"])] = kv
    missing = [(b, q) for b in BATCHES for q in QUERIES if (b, q) not in res]
    if missing:
        sys.exit(f"bench_rays printed no result for {missing}")
    return res


def load_rays(path: Path):
    a = np.fromfile(path, dtype="<f4").reshape(-1, 7)
    return (np.ascontiguousarray(a[:, 0:3]), np.ascontiguousarray(a[:, 3:6]),
            np.ascontiguousarray(a[:, 6]))


def load_triangles(path: Path):
    with open(path, "rb") as f:
        nv, nt = np.frombuffer(f.read(16), dtype="<u8")
        v = np.frombuffer(f.read(int(nv) * 12), dtype="<f4").reshape(-1, 3)
        t = np.frombuffer(f.read(int(nt) * 12), dtype="<u4").reshape(-1, 3)
    return np.ascontiguousarray(v, dtype=np.float32), np.ascontiguousarray(t, dtype=np.int32)


def embree_scene(vertices, indices, robust: bool):
    from embreex import rtcore_scene as rtcs
    from embreex.mesh_construction import TriangleMesh

    scene = rtcs.EmbreeScene(robust=robust)
    TriangleMesh(scene, vertices, indices)
    # The first run() commits (builds the BVH): do it untimed.
    one = np.zeros((1, 3), np.float32)
    scene.run(one, np.array([[0, 0, 1]], np.float32), query="INTERSECT")
    return scene


def time_run(scene, o, d, tmax, query: str, reps: int):
    """Best and median wall time of `reps` calls, the CPU/wall ratio of the best call and the
    last call's result."""
    walls, ratios, res = [], [], None
    for _ in range(reps):
        dists = tmax.copy()
        c0, w0 = time.process_time(), time.perf_counter()
        res = scene.run(o, d, dists=dists, query=query)
        w1, c1 = time.perf_counter(), time.process_time()
        walls.append(w1 - w0)
        ratios.append((c1 - c0) / max(w1 - w0, 1e-12))
    order = np.argsort(walls)
    return walls[order[0]], float(np.median(walls)), ratios[order[0]], res


def loop_overhead_ns(n: int) -> float:
    """ns per ray of embreex's loop around rtcIntersect1 on a scene with one far-away triangle
    that no ray's box test reaches (an upper bound of the binding's per-ray cost)."""
    v = np.array([[1e3, 1e3, 1e3], [1e3 + 1, 1e3, 1e3], [1e3, 1e3 + 1, 1e3]], np.float32)
    scene = embree_scene(v, np.array([[0, 1, 2]], np.int32), robust=False)
    rng = np.random.default_rng(1)
    o = rng.uniform(-1, 1, (n, 3)).astype(np.float32)
    d = rng.normal(size=(n, 3)).astype(np.float32)
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    d[:, 0] = -np.abs(d[:, 0])  # away from the triangle
    best, *_ = time_run(scene, o, d, np.full(n, np.inf, np.float32), "INTERSECT", 3)
    return best / n * 1e9


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", type=Path, default=ROOT / "benchmarks/scenes/heightfield.xml")
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--out", type=Path, default=ROOT / "target/bench")
    ap.add_argument("--robust", action="store_true", help="Embree's robust (watertight) mode")
    ap.add_argument("--skip-rust", action="store_true", help="reuse the last run's files in OUT")
    args = ap.parse_args()
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)

    ply = ROOT / "benchmarks/scenes/heightfield.ply"
    if args.scene.resolve() == (ROOT / "benchmarks/scenes/heightfield.xml") and not ply.exists():
        subprocess.run([sys.executable, "scripts/gen_heightfield.py"], cwd=ROOT, check=True)

    if args.skip_rust:
        rust = parse_results((out / "spectrace_results.txt").read_text())
    else:
        rust = run_rust(args, out)

    import embreex  # noqa: F401  (fail early with a clear message if missing)

    vertices, indices = load_triangles(out / "triangles.bin")
    t0 = time.perf_counter()
    scene = embree_scene(vertices, indices, args.robust)
    print(f"Embree: {len(indices)} triangles, scene built in {time.perf_counter() - t0:.2f} s"
          f" ({'robust' if args.robust else 'default'} mode)", file=sys.stderr)

    rows, checks = [], []
    for batch in BATCHES:
        o, d, tinf = load_rays(out / f"rays_{batch}.bin")
        oo, od, tocc = load_rays(out / f"rays_{batch}_occluded.bin")
        assert np.array_equal(o, oo) and np.array_equal(d, od)
        n = len(o)
        scene.run(o[:10000], d[:10000], query="INTERSECT")  # warm-up
        best, med, ratio, _ = time_run(scene, o, d, tinf, "INTERSECT", args.reps)
        # Distances for the checksum, from one more untimed call with output.
        full = scene.run(o, d, dists=tinf.copy(), query="INTERSECT", output=1)
        e_hit = full["geomID"] != -1
        e_t = np.where(e_hit, full["tfar"], np.inf)
        s_t = np.fromfile(out / f"hits_{batch}.bin", dtype="<f4")
        s_hit = np.isfinite(s_t)
        both = s_hit & e_hit
        rel = np.abs(s_t[both] - e_t[both]) / np.maximum(s_t[both], 1e-30)
        r = rust[(batch, "closest")]
        rows.append((batch, "closest hit", n, float(r["mrays_best"]), float(r["mrays_median"]),
                     n / best / 1e6, n / med / 1e6, ratio))
        checks.append(
            f"| {batch} | closest hit | {n:,} | {int(r['hits']):,} | {int(e_hit.sum()):,} "
            f"| {int((s_hit != e_hit).sum())} | {float(r['tsum']):.6e} "
            f"| {float(e_t[e_hit].astype(np.float64).sum()):.6e} "
            f"| {int((rel > 1e-4).sum())} | {rel.max() if rel.size else 0:.2e} |")

        best, med, ratio, res = time_run(scene, o, d, tocc, "OCCLUDED", args.reps)
        e_occ = res != -1
        s_occ = np.fromfile(out / f"occluded_{batch}.bin", dtype=np.uint8) != 0
        r = rust[(batch, "occluded")]
        rows.append((batch, "occluded", n, float(r["mrays_best"]), float(r["mrays_median"]),
                     n / best / 1e6, n / med / 1e6, ratio))
        checks.append(
            f"| {batch} | occluded | {n:,} | {int(r['hits']):,} | {int(e_occ.sum()):,} "
            f"| {int((s_occ != e_occ).sum())} | | | | |")

    overhead = loop_overhead_ns(min(1 << 20, max(len(o), 1 << 16)))

    print(f"\nspectrace vs Embree 4 ({embree_version()}), {args.scene.name}, "
          f"{len(indices):,} triangles, {args.size}x{args.size} camera rays, single-threaded, "
          f"best of {args.reps} (median in brackets):\n")
    print("| batch | query | rays | spectrace Mrays/s | Embree Mrays/s "
          "| ratio spectrace ÷ Embree | Embree CPU/wall |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
    for b, q, n, sb, sm, eb, em, ratio in rows:
        print(f"| {b} | {q} | {n:,} | {sb:.3f} ({sm:.3f}) | {eb:.3f} ({em:.3f}) "
              f"| {sb / eb:.3f} | {ratio:.2f} |")
    print(f"\nembreex per-ray loop overhead (one far-away triangle): {overhead:.0f} ns/ray "
          f"(not subtracted above).\n")
    print("| batch | query | rays | spectrace hits | Embree hits | rays that disagree "
          "| spectrace Σt (m) | Embree Σt (m) | hits with \\|Δt\\|/t > 1e-4 | max \\|Δt\\|/t |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for c in checks:
        print(c)
    return 0


def embree_version() -> str:
    try:
        from importlib.metadata import version
        return "embreex " + version("embreex")
    except Exception:  # noqa: BLE001
        return "?"


if __name__ == "__main__":
    sys.exit(main())
