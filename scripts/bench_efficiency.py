#!/usr/bin/env python3
"""Rendering efficiency of spectrace against Mitsuba 3.9.1 on the same Mitsuba XML scene files.

How to run (from the repository root):

    pip install -r scripts/bench-requirements.txt    # mitsuba 3.9.1, drjit, numpy, OpenImageIO
    # for Mitsuba's llvm_ad_spectral variant (Debian 12):
    #   apt-get update && apt-get install -y libllvm19
    export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1
    cargo build --release      # the script only builds if target/release/spectrace is missing
    python3 scripts/bench_efficiency.py

    # quick check (a few seconds of rendering):
    python3 scripts/bench_efficiency.py --spp 2 --res 64

Options: --scenes PATH[@WxH],... (default: the spectral Cornell box
tests/reference/cornell/scene.xml at 256×256, and benchmarks/scenes/heightfield.xml at its own
256×256; the PLY is made with scripts/gen_heightfield.py if missing), --spp 64 (or a list such
as 64,256: each count is measured in turn and the summary has a column per count), --threads 2
(for both renderers; Mitsuba through dr.set_thread_count), --repeats 1, --res N or WxH (film
size for every scene), --configs (a subset of spectrace, scalar_spectral/independent,
scalar_spectral/ldsampler, llvm_ad_spectral/independent, llvm_ad_spectral/ldsampler; a bare
variant or sampler name selects both of its configurations), --skip-spectrace, --build (run
`cargo build --release` first even if the binary exists). `--help` lists them all.

Definitions:
  * Efficiency = 1 / (relative variance per sample × time per sample), in 1/s, i.e. samples
    per second ÷ relative variance per sample. Higher is better: a W×H image rendered for T
    seconds has a relative (per-pixel-averaged) variance of about W·H / (efficiency · T).
  * Variance per sample: the scene is rendered twice, with seeds A and B, at N spp each; with
    Y the luminance,
        var = mean_pixels((Y_A − Y_B)²) / 2 × N,    relative var = var / mean_pixels((Y_A+Y_B)/2)².
    (E[(A − B)²] = 2·Var(one image), and Var(one image) = Var(one sample)/N.) spectrace's EXR has
    a Y channel; Mitsuba's films in these XMLs use pixel_format xyz, so Mitsuba's image tensor
    is X, Y, Z (checked at run time from the film's bitmap; RGB would be converted with the
    linear-sRGB weights 0.2126, 0.7152, 0.0722). The scale of Y (cd/m² or Mitsuba's unitless
    film) cancels in the relative variance.
  * Time per sample = render time / (width × height × N), the mean over the A and B renders.
    Render time only: spectrace's EXR attribute `spectrace:renderTimeSeconds`; Mitsuba's wall
    clock around mi.render(scene, spp=N, seed=s) + dr.eval(img) + dr.sync_thread(), after one
    warm-up render at the same spp (thread pool start-up and, for LLVM, JIT compilation are not
    counted; Dr.Jit's kernel cache makes the timed renders reuse the warm-up's kernels). Each
    Mitsuba configuration (variant and sampler) runs in its own worker process holding one scene
    at a time: loading a second scene into an LLVM process changes the traced kernels and would
    put a JIT compilation back into the timed render. The scene is loaded (BVH built) before
    and outside the timing, as spectrace's render time also excludes loading.
  * With --repeats R > 1, each repeat uses a fresh pair of seeds; the table shows the median of
    the R time-per-sample values and the mean of the R relative-variance estimates.
  * Ratio column: spectrace's efficiency ÷ this configuration's (> 1: spectrace is more
    efficient).

Configurations: spectrace (`target/release/spectrace render SCENE.xml --spp N --seed S
--threads T -o OUT.exr --png TMP.png --quiet`), and Mitsuba 3.9.1 variants scalar_spectral and
llvm_ad_spectral, each with the `independent` and the `ldsampler` sampler. The sampler and,
with --res or a scene's @WxH, the film size are changed by rewriting the XML text into a
temporary file next to the original (so that relative mesh paths resolve), deleted afterwards.
spectrace renders the rewritten file with the `independent` sampler. ldsampler rounds the spp up
to a power of two; the actual sample count Mitsuba used is the one counted (and noted).

Interleaving: for each scene, for each repeat, every configuration renders its A then its B
image in turn (spectrace, then each Mitsuba configuration), so that load from other processes
hits all of them alike. The load average is recorded with every render.

Prints the machine, date, versions and one Markdown table on stdout (progress on stderr) and
writes target/bench/efficiency.json. If any part is skipped (a Mitsuba variant cannot start, a
scene cannot load, spectrace is missing or fails), the rest runs, the report says what was
skipped, and the exit code is 1. Uses Mitsuba's Python API only.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import re
import signal
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from bench_common import cpu_model, loadavg, read_exr

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT / "target" / "bench"
WORK = BENCH / "efficiency"
# SPECTRACE_BIN=path runs another spectrace build (e.g. an older commit's, for a same-run baseline)
SPECTRACE = Path(os.environ.get("SPECTRACE_BIN", ROOT / "target" / "release" / "spectrace")).resolve()
HEIGHTFIELD_XML = ROOT / "benchmarks" / "scenes" / "heightfield.xml"
HEIGHTFIELD_PLY = ROOT / "benchmarks" / "scenes" / "heightfield.ply"
DEFAULT_SCENES = "tests/reference/cornell/scene.xml@256x256,benchmarks/scenes/heightfield.xml"
DEFAULT_LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"

VARIANTS = ("scalar_spectral", "llvm_ad_spectral")
SAMPLERS = ("independent", "ldsampler")
ALL_CONFIGS = ["spectrace"] + [f"{v}/{s}" for v in VARIANTS for s in SAMPLERS]

SEED_BASE = 1  # repeat r uses seeds SEED_BASE + 2r (A) and SEED_BASE + 2r + 1 (B)
WARMUP_SEED = 999_999
SRGB_Y = (0.2126, 0.7152, 0.0722)


def log(*a) -> None:
    print(*a, file=sys.stderr, flush=True)


# --------------------------------------------------------------------------- XML rewriting


def rewrite_xml(text: str, sampler: str, res: tuple[int, int] | None) -> str:
    """The scene text with the sensor's sampler type set to `sampler` and, if `res` is given,
    the film's width and height set to it."""
    new, n = re.subn(r'(<sampler\s+type=")[^"]*(")', rf"\g<1>{sampler}\g<2>", text)
    if n == 0:  # no sampler element: add one to the (single) sensor
        new, n = re.subn(
            r"(<sensor\b[^>]*>)", rf'\1\n        <sampler type="{sampler}"/>', text, count=1
        )
        if n == 0:
            raise ValueError("no <sensor> element to put a sampler in")
    text = new
    if res is None:
        return text
    m = re.search(r"<film\b[^>]*?(/?)>", text)
    if m is None:
        raise ValueError("no <film> element")
    if m.group(1) == "/":  # <film type="hdrfilm"/>: open it up
        opening = m.group(0)[:-2].rstrip() + ">"
        text = text[: m.start()] + opening + "</film>" + text[m.end() :]
        m = re.search(r"<film\b[^>]*>", text)
    end = text.index("</film>", m.end())
    body = text[m.end() : end]
    for name, value in (("width", res[0]), ("height", res[1])):
        pat = rf'(<integer\s+name="{name}"\s+value=")[^"]*(")'
        body, n = re.subn(pat, rf"\g<1>{value}\g<2>", body)
        if n == 0:
            body = f'\n            <integer name="{name}" value="{value}"/>' + body
    return text[: m.end()] + body + text[end:]


def film_size(text: str) -> tuple[int, int]:
    m = re.search(r"<film\b.*?</film>", text, re.S)
    size = [768, 576]  # Mitsuba's hdrfilm defaults
    if m:
        for i, name in enumerate(("width", "height")):
            v = re.search(rf'<integer\s+name="{name}"\s+value="(\d+)"', m.group(0))
            if v:
                size[i] = int(v.group(1))
    return size[0], size[1]


def parse_res(s: str) -> tuple[int, int]:
    w, _, h = s.lower().partition("x")
    return int(w), int(h or w)


# --------------------------------------------------------------------------- Mitsuba worker


def film_luminance(film, img) -> tuple[np.ndarray, list[str]]:
    """Y of a rendered image tensor, and the film's channel names (X, Y, Z for pixel_format xyz;
    RGB is converted with the linear-sRGB weights)."""
    a = np.array(img, dtype=np.float64)
    names = [f.name for f in film.bitmap().struct_()]
    return _luminance(a, names), names


def _luminance(a: np.ndarray, names: list[str]) -> np.ndarray:
    if a.ndim == 2:
        a = a[..., None]
    if "Y" in names:
        return a[..., names.index("Y")]
    if all(c in names for c in "RGB"):
        return sum(w * a[..., names.index(c)] for w, c in zip(SRGB_Y, "RGB"))
    if a.shape[-1] == 1:
        return a[..., 0]
    raise RuntimeError(f"cannot find luminance in film channels {names}")


def mitsuba_worker(variant: str, threads: int) -> None:
    """Line protocol on stdin/stdout: '@@' + JSON per reply."""
    # Keep library chatter off the protocol channel: Mitsuba's logger writes to file
    # descriptor 1 from C++ (e.g. ldsampler's rounding warning, with colour codes that spill
    # onto the next line), so fd 1 is pointed at stderr and the replies use a copy of the pipe.
    sys.stdout.flush()
    out = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
    sys.stdout = sys.stderr

    def reply(obj: dict) -> None:
        out.write("@@" + json.dumps(obj) + "\n")
        out.flush()

    try:
        import drjit as dr
        import mitsuba as mi

        mi.set_variant(variant)
        dr.set_thread_count(threads)
        reply(
            {
                "ready": True,
                "mitsuba": mi.__version__,
                "drjit": dr.__version__,
                "threads": int(dr.thread_count()),
            }
        )
    except Exception as e:  # noqa: BLE001 — report any start-up failure to the driver
        reply({"ready": False, "error": f"{type(e).__name__}: {e}"})
        return

    import gc

    scenes: dict = {}  # at most one: "current"

    def render(scene, spp: int, seed: int):
        t0 = time.perf_counter()
        img = mi.render(scene, spp=spp, seed=seed)
        dr.eval(img)
        dr.sync_thread()
        return img, time.perf_counter() - t0

    for line in sys.stdin:
        req = json.loads(line)
        cmd = req["cmd"]
        try:
            if cmd == "quit":
                break
            if cmd == "load":
                scenes.clear()
                gc.collect()
                t0 = time.perf_counter()
                scene = mi.load_file(req["path"])
                t_load = time.perf_counter() - t0
                scenes["current"] = scene
                _, warm = render(scene, req["spp"], WARMUP_SEED)
                reply({"ok": True, "load_seconds": t_load, "warmup_seconds": warm})
            elif cmd == "render":
                scene = scenes["current"]
                img, secs = render(scene, req["spp"], req["seed"])
                sensor = scene.sensors()[0]
                y, channels = film_luminance(sensor.film(), img)
                np.save(req["out"], y.astype(np.float32))
                reply(
                    {
                        "ok": True,
                        "seconds": secs,
                        "spp": int(sensor.sampler().sample_count()),
                        "channels": channels,
                    }
                )
            elif cmd == "drop":
                scenes.clear()
                gc.collect()
                reply({"ok": True})
            else:
                reply({"ok": False, "error": f"unknown command {cmd}"})
        except Exception as e:  # noqa: BLE001
            reply({"ok": False, "error": f"{type(e).__name__}: {e}"})


class MitsubaWorker:
    def __init__(self, variant: str, threads: int):
        self.variant = variant
        self.proc = subprocess.Popen(
            [sys.executable, __file__, "--mitsuba-worker", variant, "--threads", str(threads)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            cwd=ROOT,
        )
        try:
            self.info = self._read()
        except RuntimeError as e:
            self.info = {"ready": False, "error": str(e)}

    def _read(self) -> dict:
        for line in self.proc.stdout:
            i = line.find("@@")
            if i >= 0:
                return json.loads(line[i + 2 :])
        raise RuntimeError(f"Mitsuba worker {self.variant} exited (code {self.proc.wait()})")

    def ask(self, **req) -> dict:
        if self.proc.poll() is not None:
            return {"ok": False, "error": f"worker exited (code {self.proc.returncode})"}
        try:
            self.proc.stdin.write(json.dumps(req) + "\n")
            self.proc.stdin.flush()
            return self._read()
        except (RuntimeError, BrokenPipeError) as e:
            return {"ok": False, "error": str(e)}

    def close(self, force: bool = False) -> None:
        if force and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if self.proc.poll() is None:
            try:
                self.proc.stdin.write(json.dumps({"cmd": "quit"}) + "\n")
                self.proc.stdin.flush()
                self.proc.wait(timeout=60)
            except (BrokenPipeError, subprocess.TimeoutExpired):
                self.proc.kill()
                self.proc.wait()


# --------------------------------------------------------------------------- spectrace


def spectrace_render(
    scene: Path, spp: int, seed: int, threads: int, out: Path
) -> tuple[float, np.ndarray]:
    """Returns (render seconds from the EXR header, luminance Y)."""
    png = out.with_suffix(".png")
    cmd = [str(SPECTRACE), "render", str(scene), "--spp", str(spp), "--seed", str(seed)]
    cmd += ["--threads", str(threads), "-o", str(out), "--png", str(png), "--quiet"]
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    png.unlink(missing_ok=True)
    if r.returncode != 0:
        raise RuntimeError(
            f"`{' '.join(cmd)}` failed with exit code {r.returncode}:\n{r.stderr.strip()[-2000:]}"
        )
    chans, attrs = read_exr(out)
    return float(attrs["spectrace:renderTimeSeconds"]), chans["Y"]


# --------------------------------------------------------------------------- machine


def git_head() -> str:
    r = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
    )
    head = r.stdout.strip() or "unknown"
    dirty = subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=no"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    ).stdout.strip()
    return head + (" (with uncommitted changes)" if dirty else "")


# --------------------------------------------------------------------------- driver


def select_configs(spec: str) -> list[str]:
    chosen = []
    for tok in [t.strip() for t in spec.split(",") if t.strip()]:
        tok = tok.replace(":", "/")
        match = [c for c in ALL_CONFIGS if c == tok or tok in c.split("/")]
        if not match:
            raise SystemExit(f"unknown configuration {tok!r}; known: {', '.join(ALL_CONFIGS)}")
        chosen += [c for c in match if c not in chosen]
    return [c for c in ALL_CONFIGS if c in chosen]  # fixed order


def rel_var_per_sample(a: np.ndarray, b: np.ndarray, spp: int) -> float:
    var = float(np.mean((a - b) ** 2)) / 2.0 * spp
    mean = float(np.mean(0.5 * (a + b)))
    return var / mean**2 if mean != 0 else float("nan")


def main() -> int:
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument(
        "--scenes",
        default=DEFAULT_SCENES,
        help="comma-separated Mitsuba XML files, each optionally PATH@WxH to set its film size "
        f"(default: {DEFAULT_SCENES})",
    )
    ap.add_argument(
        "--spp",
        default="64",
        help="samples per pixel of each render; a comma-separated list (e.g. 64,256) measures "
        "each count in turn and prints a row per scene, configuration and count",
    )
    ap.add_argument("--threads", type=int, default=2, help="threads for both renderers")
    ap.add_argument("--repeats", type=int, default=1, help="interleaved repeats (median time)")
    ap.add_argument(
        "--configs",
        default=",".join(ALL_CONFIGS),
        help="comma-separated subset of: " + ", ".join(ALL_CONFIGS),
    )
    ap.add_argument("--skip-spectrace", action="store_true")
    ap.add_argument("--res", help="film size for every scene: N (square) or WxH")
    ap.add_argument("--build", action="store_true", help="cargo build --release first")
    ap.add_argument("--mitsuba-worker", metavar="VARIANT", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.mitsuba_worker:
        mitsuba_worker(args.mitsuba_worker, args.threads)
        return 0

    # SIGTERM unwinds like Ctrl-C, so that the temporary XML files are removed.
    signal.signal(signal.SIGTERM, on_sigterm)
    configs = select_configs(args.configs)
    try:
        spps = [int(t) for t in str(args.spp).split(",") if t.strip()]
    except ValueError:
        ap.error(f"--spp {args.spp}: expected counts separated by commas, e.g. 64,256")
    if not spps or min(spps) < 1:
        ap.error(f"--spp {args.spp}: every count must be at least 1")
    if args.skip_spectrace and "spectrace" in configs:
        configs.remove("spectrace")
    res_all = parse_res(args.res) if args.res else None
    WORK.mkdir(parents=True, exist_ok=True)
    notes: list[str] = []  # skipped parts (exit code 1)
    remarks: list[str] = []  # worth knowing, not a skip
    t_start = time.time()
    load_start = os.getloadavg() if hasattr(os, "getloadavg") else (float("nan"),) * 3
    if "DRJIT_LIBLLVM_PATH" not in os.environ and Path(DEFAULT_LLVM).exists():
        os.environ["DRJIT_LIBLLVM_PATH"] = DEFAULT_LLVM  # inherited by the workers

    # scenes
    scenes = []
    for tok in [t.strip() for t in args.scenes.split(",") if t.strip()]:
        path_s, _, res_s = tok.partition("@")
        path = Path(path_s) if Path(path_s).exists() else ROOT / path_s  # cwd, then the repo
        path = path.resolve()
        res = res_all or (parse_res(res_s) if res_s else None)
        if path == HEIGHTFIELD_XML.resolve() and not HEIGHTFIELD_PLY.exists():
            log("generating benchmarks/scenes/heightfield.ply ...")
            r = subprocess.run(
                [sys.executable, str(ROOT / "scripts" / "gen_heightfield.py")],
                cwd=ROOT,
                capture_output=True,
                text=True,
            )
            if r.returncode != 0:
                notes.append(f"gen_heightfield.py failed, scene {path_s} skipped: {r.stderr}")
                continue
        if not path.exists():
            notes.append(f"scene {path_s} not found, skipped")
            continue
        try:
            path.relative_to(ROOT)
            name = str(path.relative_to(ROOT))
        except ValueError:
            name = str(path)
        scenes.append({"name": name, "path": path, "res": res})

    # spectrace
    st_version = ""
    st_binary = {}
    if "spectrace" in configs:
        if args.build or not SPECTRACE.exists():
            log("cargo build --release ...")
            r = subprocess.run(
                ["cargo", "build", "--release"], cwd=ROOT, capture_output=True, text=True
            )
            if r.returncode != 0:
                notes.append(f"cargo build --release failed:\n{r.stderr.strip()[-2000:]}")
        if SPECTRACE.exists():
            st_version = subprocess.run(
                [str(SPECTRACE), "--version"], capture_output=True, text=True
            ).stdout.strip()
            mtime = datetime.datetime.fromtimestamp(SPECTRACE.stat().st_mtime)
            st_binary = {"path": str(SPECTRACE), "mtime": mtime.isoformat()}
        else:
            notes.append("target/release/spectrace is missing; spectrace skipped")
            configs.remove("spectrace")

    # Mitsuba workers, one per configuration (variant and sampler). A worker holds one scene at
    # a time and nothing else is loaded between its warm-up and its timed renders: in the LLVM
    # variant, loading another scene into the same process changes the traced kernels (the
    # registry of instances that virtual calls dispatch over) and forces a fresh JIT
    # compilation inside the timed render.
    workers: dict[str, MitsubaWorker] = {}
    versions: dict[str, str] = {}
    mi_threads = {}
    failed_variants: dict[str, str] = {}
    for c in [c for c in configs if c != "spectrace"]:
        v = c.split("/")[0]
        if v in failed_variants:
            notes.append(f"Mitsuba {c} skipped: variant {v} could not start")
            continue
        log(f"starting Mitsuba {c} ...")
        w = MitsubaWorker(v, args.threads)
        if not w.info.get("ready"):
            failed_variants[v] = str(w.info.get("error"))
            notes.append(f"Mitsuba {c} skipped: variant {v} could not start: {w.info.get('error')}")
            w.close()
            continue
        versions = {"mitsuba": w.info["mitsuba"], "drjit": w.info["drjit"]}
        mi_threads[v] = w.info["threads"]
        workers[c] = w
    configs = [c for c in configs if c == "spectrace" or c in workers]

    # measurements, interleaved
    results: list[dict] = []
    interrupted = False
    try:
        for sc in scenes:
            text = sc["path"].read_text()
            tmp: dict[str, Path] = {}
            try:
                for s in SAMPLERS:
                    p = sc["path"].parent / f".bench_efficiency_{os.getpid()}_{s}.xml"
                    p.write_text(rewrite_xml(text, s, sc["res"]))
                    tmp[s] = p
                w_px, h_px = film_size(tmp["independent"].read_text())
                sc["width"], sc["height"] = w_px, h_px
                for spp_req in spps:
                    log(f"scene {sc['name']}: {w_px}×{h_px}, {spp_req} spp")
                    active = []
                    rows = {}
                    for c in configs:
                        rows[c] = {"scene": sc["name"], "config": c, "spp": spp_req, "runs": []}
                        if c == "spectrace":
                            active.append(c)
                            continue
                        s = c.split("/")[1]
                        rep = workers[c].ask(cmd="load", path=str(tmp[s]), spp=spp_req)
                        if not rep.get("ok"):
                            notes.append(f"{c} could not load {sc['name']}, skipped: {rep.get('error')}")
                            continue
                        rows[c]["load_seconds"] = rep["load_seconds"]
                        rows[c]["warmup_seconds"] = rep["warmup_seconds"]
                        log(
                            f"  {c:30s} loaded in {rep['load_seconds']:.2f} s, "
                            f"warm-up {rep['warmup_seconds']:.2f} s"
                        )
                        active.append(c)
                    for r in range(args.repeats):
                        seeds = (SEED_BASE + 2 * r, SEED_BASE + 2 * r + 1)
                        for c in list(active):
                            run = {"seeds": list(seeds), "seconds": [], "load1": []}
                            ys = []
                            try:
                                for seed in seeds:
                                    tag = c.replace("/", "_")
                                    run["load1"].append(loadavg())
                                    if c == "spectrace":
                                        out = WORK / f"{tag}_{seed}.exr"
                                        secs, y = spectrace_render(
                                            tmp["independent"], spp_req, seed, args.threads, out
                                        )
                                        spp = spp_req
                                    else:
                                        out = WORK / f"{tag}_{seed}.npy"
                                        rep = workers[c].ask(
                                            cmd="render", spp=spp_req, seed=seed, out=str(out)
                                        )
                                        if not rep.get("ok"):
                                            raise RuntimeError(rep.get("error"))
                                        secs, spp = rep["seconds"], rep["spp"]
                                        rows[c]["mitsuba_channels"] = rep["channels"]
                                        y = np.load(out).astype(np.float64)
                                    run["seconds"].append(secs)
                                    ys.append(y)
                                    log(
                                        f"  {c:30s} seed {seed:3d}: {spp} spp, {secs:8.3f} s "
                                        f"(load {run['load1'][-1]:.2f})"
                                    )
                            except RuntimeError as e:
                                notes.append(f"{c} failed on {sc['name']}, skipped: {e}")
                                active.remove(c)
                                rows[c]["failed"] = True
                                continue
                            if spp != spp_req:
                                msg = f"{c} used {spp} spp instead of {spp_req} (counted as {spp})"
                                if msg not in remarks:
                                    remarks.append(msg)
                            run["spp"] = spp
                            run["time_per_sample"] = float(np.mean(run["seconds"])) / (
                                w_px * h_px * spp
                            )
                            run["rel_var_per_sample"] = rel_var_per_sample(ys[0], ys[1], spp)
                            run["mean_y"] = float(np.mean(0.5 * (ys[0] + ys[1])))
                            rows[c]["runs"].append(run)
                    for c in configs:
                        row = rows[c]
                        if not row["runs"] or row.get("failed"):
                            continue
                        tps = statistics.median(run["time_per_sample"] for run in row["runs"])
                        rv = float(np.mean([run["rel_var_per_sample"] for run in row["runs"]]))
                        row["time_per_sample"] = tps
                        row["samples_per_second"] = 1.0 / tps
                        row["rel_var_per_sample"] = rv
                        row["efficiency"] = 1.0 / (rv * tps)
                        results.append(row)
                    for w in workers.values():
                        w.ask(cmd="drop")
            finally:
                for p in tmp.values():
                    p.unlink(missing_ok=True)
    except KeyboardInterrupt:
        interrupted = True
        notes.append("interrupted; the table has the scenes finished so far")
    finally:
        for w in workers.values():
            w.close(force=interrupted)

    # report
    load_end = os.getloadavg() if hasattr(os, "getloadavg") else (float("nan"),) * 3
    for row in results:
        st = next(
            (
                x
                for x in results
                if x["scene"] == row["scene"]
                and x["spp"] == row["spp"]
                and x["config"] == "spectrace"
            ),
            None,
        )
        row["spectrace_ratio"] = st["efficiency"] / row["efficiency"] if st else None

    def label(c: str) -> str:
        return "spectrace (path)" if c == "spectrace" else f"Mitsuba {c}"

    lines = [
        "| scene | spp | configuration | samples/s (M) | relative variance per sample "
        "| efficiency (1/s) | spectrace ÷ this |",
        "| --- | ---: | --- | ---: | ---: | ---: | ---: |",
    ]
    for row in results:
        ratio = "n/a" if row["spectrace_ratio"] is None else f"{row['spectrace_ratio']:.2f}"
        lines.append(
            f"| {row['scene']} ({row_size(scenes, row['scene'])}) | {row['spp']} "
            f"| {label(row['config'])} "
            f"| {row['samples_per_second'] / 1e6:.3f} | {row['rel_var_per_sample']:.3e} "
            f"| {row['efficiency']:.3e} | {ratio} |"
        )
    # the summary: spectrace's efficiency ratio against each Mitsuba configuration, one column
    # per sample count
    mi_configs = [c for c in configs if c != "spectrace"]
    if mi_configs and any(r["config"] == "spectrace" for r in results):
        lines += [
            "",
            "| scene | spectrace ÷ "
            + " | spectrace ÷ ".join(f"{c} at {n} spp" for c in mi_configs for n in spps)
            + " |",
            "| --- |" + " ---: |" * (len(mi_configs) * len(spps)),
        ]
        for sc in scenes:
            cells = []
            for c in mi_configs:
                for n in spps:
                    r = next(
                        (
                            x
                            for x in results
                            if x["scene"] == sc["name"] and x["config"] == c and x["spp"] == n
                        ),
                        None,
                    )
                    ok = r is not None and r["spectrace_ratio"] is not None
                    cells.append(f"{r['spectrace_ratio']:.2f}" if ok else "n/a")
            lines.append(f"| {sc['name']} | " + " | ".join(cells) + " |")

    head = [
        f"Date: {datetime.datetime.now().isoformat(timespec='seconds')}",
        f"Machine: {os.cpu_count()} × {cpu_model()}; load average (1, 5, 15 min) at start "
        f"{fmt_load(load_start)}, at end {fmt_load(load_end)}",
        f"Versions: Mitsuba {versions.get('mitsuba', 'n/a')} (Dr.Jit {versions.get('drjit', 'n/a')}), "
        f"{st_version or 'spectrace n/a'} (git {git_head()}"
        + (f", binary built {st_binary['mtime']}" if st_binary else "")
        + f"), Python {platform.python_version()}",
        f"Settings: {', '.join(map(str, spps))} spp per image, two images (seeds A, B) per configuration and "
        f"repeat, {args.repeats} repeat(s), {args.threads} threads"
        + (f" (Mitsuba reports {mi_threads})" if mi_threads else ""),
    ]
    chans = sorted({",".join(r["mitsuba_channels"]) for r in results if "mitsuba_channels" in r})
    if chans:
        head.append(
            f"Luminance: spectrace's EXR channel Y; Mitsuba's film channels {' / '.join(chans)} "
            "(Y taken directly" + (", or from linear sRGB)" if any("R" in c for c in chans) else ")")
        )
    out = head + ["", "\n".join(lines)]
    for n in remarks:
        out += ["", "Remark: " + n]
    for n in notes:
        out += ["", "Skipped: " + n]
    out += ["", f"Total benchmark time: {time.time() - t_start:.0f} s"]
    print("\n".join(out))

    (BENCH / "efficiency.json").write_text(
        json.dumps(
            {
                "date": datetime.datetime.now().isoformat(timespec="seconds"),
                "machine": {
                    "cpu": cpu_model(),
                    "cpus": os.cpu_count(),
                    "loadavg_start": list(load_start),
                    "loadavg_end": list(load_end),
                },
                "versions": versions
                | {"spectrace": st_version, "git": git_head(), "python": platform.python_version()},
                "spectrace_binary": st_binary,
                "settings": {
                    "spp": spps,
                    "threads": args.threads,
                    "mitsuba_threads": mi_threads,
                    "repeats": args.repeats,
                    "configs": configs,
                },
                "scenes": [
                    {k: (str(v) if isinstance(v, Path) else v) for k, v in sc.items()}
                    for sc in scenes
                ],
                "results": results,
                "skipped": notes,
                "remarks": remarks,
            },
            indent=2,
        )
    )
    log(f"wrote {(BENCH / 'efficiency.json').relative_to(ROOT)}")
    return 0 if not notes else 1


def on_sigterm(signum, frame) -> None:
    raise KeyboardInterrupt


def fmt_load(t) -> str:
    return ", ".join(f"{x:.2f}" for x in t)


def row_size(scenes: list[dict], name: str) -> str:
    sc = next((s for s in scenes if s["name"] == name), None)
    return f"{sc['width']}×{sc['height']}" if sc and "width" in sc else "?"


if __name__ == "__main__":
    sys.exit(main())
