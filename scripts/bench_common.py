"""Helpers shared by the benchmark scripts (bench_mitsuba.py, bench_efficiency.py): reading an
EXR's channels and attributes, and describing the machine. Standard library, numpy and
OpenImageIO (imported when an EXR is read)."""

from __future__ import annotations

import os
import platform
from pathlib import Path

import numpy as np


def read_exr(path: Path) -> tuple[dict[str, np.ndarray], dict]:
    """The channels of an image (float64 arrays by channel name) and its extra attributes."""
    import OpenImageIO as oiio

    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise RuntimeError(f"cannot open {path}: {oiio.geterror()}")
    spec = inp.spec()
    px = inp.read_image(0, 0, 0, spec.nchannels, "float")
    inp.close()
    chans = {name: px[..., i].astype(np.float64) for i, name in enumerate(spec.channelnames)}
    attrs = {a.name: a.value for a in spec.extra_attribs}
    return chans, attrs


def loadavg() -> float:
    """The 1-minute load average, NaN where the system has none."""
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def cpu_model() -> str:
    """The CPU's model name."""
    try:
        for ln in Path("/proc/cpuinfo").read_text().splitlines():
            if ln.startswith("model name"):
                return ln.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"
