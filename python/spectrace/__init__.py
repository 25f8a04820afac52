"""spectrace: a spectral path tracer whose numbers mean something, from Python.

Render a scene (a file, TOML text, or one built here) and read its pixels as NumPy arrays
with stated units: ``image.luminance`` in cd/m², ``image.xyz`` on the luminance scale,
``image.radiance`` in W·m⁻²·sr⁻¹, ``image.spectral`` in W·m⁻²·sr⁻¹·nm⁻¹.

    import spectrace
    scene = (spectrace.Scene.builder()
             .camera(eye=[0, 1, 0], target=[0, 0, 0], up=[0, 0, 1], fov="2 deg")
             .film(16, 16)
             .material("grey", type="diffuse", reflectance=0.18)
             .shape("rectangle", material="grey",
                    transform=[{"scale": 10}, {"rotate": {"axis": [1, 0, 0], "angle": "-90 deg"}}])
             .light("point", position=[0, 2, 0], power="800 lm", spectrum="cie-a")
             .build())
    image = spectrace.render(scene, spp=64)
    value, standard_error = image.mean_luminance()      # cd/m²

Quantities are strings with units, exactly as in scene files ("800 lm", "40 deg", "6500 K");
coordinates are numbers in the scene's length unit (metres unless ``length_unit`` says).
Rendering releases the GIL; Ctrl-C stops it and raises KeyboardInterrupt.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._native import SpectraceError

__all__ = [
    "Image",
    "MeterReading",
    "Scene",
    "SceneBuilder",
    "SpectraceError",
    "Spectrum",
    "lens",
    "material_albedo",
    "measure",
    "render",
    "spectrum",
]


class Scene:
    """A render-ready scene: ``Scene.load(path)``, ``Scene.from_toml(text)`` or
    ``Scene.builder()...build()``."""

    def __init__(self, native: Any) -> None:
        self._native = native

    @staticmethod
    def load(path: Union[str, os.PathLike], defines: Optional[Dict[str, str]] = None) -> "Scene":
        """A scene file: spectrace TOML, or Mitsuba 3 XML with values for its ``$name``
        parameters."""
        pairs = [(str(k), str(v)) for k, v in (defines or {}).items()]
        return Scene(_native.load(os.fspath(path), pairs))

    @staticmethod
    def from_toml(text: str, folder: Union[str, os.PathLike] = ".") -> "Scene":
        """A scene from TOML text; relative file names resolve against ``folder``."""
        folder = os.fspath(folder)
        name = "TOML text" if folder == "." else os.path.join(folder, "TOML text")
        return Scene(_native.from_toml(text, name))

    @staticmethod
    def builder() -> "SceneBuilder":
        """A scene in code, mirroring the TOML format table by table."""
        return SceneBuilder()

    @property
    def notes(self) -> List[str]:
        """What the loader noted without refusing the scene (how Mitsuba features were read)."""
        return list(self._native.notes)

    def __repr__(self) -> str:
        return repr(self._native)


class SceneBuilder:
    """Builds a scene table by table, with the scene format's keys and quantity strings.

    Every method mirrors a TOML table: ``camera(**keys)`` is ``[camera]``,
    ``material(name, **keys)`` is ``[materials.NAME]``, ``shape(type, **keys)``,
    ``light(type, **keys)`` and ``meter(type, **keys)`` are ``[[shapes]]``, ``[[lights]]`` and
    ``[[sensors]]`` entries. ``build()`` loads the result through the same loader as a file,
    so errors name the field (``lights[0].power``) and the line of ``to_toml()``'s text.
    """

    def __init__(self) -> None:
        self._root: Dict[str, Any] = {}
        self._folder = "."

    def folder(self, folder: Union[str, os.PathLike]) -> "SceneBuilder":
        """Where relative file names (meshes, spectra, luminaires) resolve."""
        self._folder = os.fspath(folder)
        return self

    def scene(self, **keys: Any) -> "SceneBuilder":
        """``[scene]``: ``length_unit``, ``wavelength_range``."""
        self._root.setdefault("scene", {}).update(keys)
        return self

    def camera(self, **keys: Any) -> "SceneBuilder":
        """``[camera]``: ``eye``, ``target``, ``up``, ``fov`` ("40 deg"), ``type``, …"""
        self._root["camera"] = dict(keys)
        return self

    def film(self, width: int, height: int, **keys: Any) -> "SceneBuilder":
        """``[film]``: size in pixels, and ``spp``, ``filter``, ``spectral_bins``, …"""
        self._root["film"] = {"width": width, "height": height, **keys}
        return self

    def integrator(self, type: str, **keys: Any) -> "SceneBuilder":
        """``[integrator]``: ``type`` ("path", "bdpt", …), ``max_depth``, …"""
        self._root["integrator"] = {"type": type, **keys}
        return self

    def material(self, name: str, **keys: Any) -> "SceneBuilder":
        """``[materials.NAME]``: ``type`` ("diffuse", "dielectric", …) and its keys."""
        self._root.setdefault("materials", {})[name] = dict(keys)
        return self

    def shape(self, type: str, **keys: Any) -> "SceneBuilder":
        """A ``[[shapes]]`` entry: "sphere", "rectangle", "box", "disk" or "obj"."""
        self._root.setdefault("shapes", []).append({"type": type, **keys})
        return self

    def light(self, type: str, **keys: Any) -> "SceneBuilder":
        """A ``[[lights]]`` entry: "point", "spot", "directional", "environment", …"""
        self._root.setdefault("lights", []).append({"type": type, **keys})
        return self

    def meter(self, type: str, **keys: Any) -> "SceneBuilder":
        """A ``[[sensors]]`` entry (illuminance meter): "point" or "grid"."""
        self._root.setdefault("sensors", []).append({"type": type, **keys})
        return self

    def to_toml(self) -> str:
        """The scene format's TOML text that ``build()`` loads."""
        return _native.dict_to_toml(self._root)

    def build(self) -> Scene:
        """Loads and builds the scene (SpectraceError naming the field when it is wrong)."""
        name = os.path.join(self._folder, "scene builder")
        if self._folder == ".":
            name = "scene builder"
        return Scene(_native.from_toml(self.to_toml(), name))


class Image:
    """A rendered image. Arrays are ``float32``, rows from the top of the image."""

    def __init__(self, native: Any) -> None:
        self._native = native
        self._xyz: Optional[np.ndarray] = None

    @property
    def width(self) -> int:
        return self._native.width

    @property
    def height(self) -> int:
        return self._native.height

    @property
    def spp(self) -> int:
        """Samples per pixel taken everywhere."""
        return self._native.spp

    @property
    def complete(self) -> bool:
        """Whether every sample asked for was taken (False when a time limit or a target
        error ended the render first; ``stop_reason`` says which)."""
        return self._native.complete

    @property
    def stop_reason(self) -> str:
        """Why the render ended: "complete", "time limit" or "target error"."""
        return self._native.stop_reason

    @property
    def metadata(self) -> Dict[str, str]:
        """The attributes ``spectrace render`` writes to the EXR header."""
        return dict(self._native.metadata)

    def _plane(self, data: bytes, *shape: int) -> np.ndarray:
        a = np.frombuffer(data, dtype="<f4").reshape(shape)
        a.flags.writeable = False
        return a

    @property
    def xyz(self) -> np.ndarray:
        """CIE 1931 X, Y, Z, shape (height, width, 3), on the luminance scale (Y in cd/m²)."""
        if self._xyz is None:
            self._xyz = self._plane(self._native.xyz_bytes(), self.height, self.width, 3)
        return self._xyz

    @property
    def luminance(self) -> np.ndarray:
        """Luminance (CIE Y) in cd/m², shape (height, width)."""
        return self.xyz[:, :, 1]

    @property
    def radiance(self) -> np.ndarray:
        """Radiance over the scene's wavelength range in W·m⁻²·sr⁻¹, shape (height, width)."""
        return self._plane(self._native.radiance_bytes(), self.height, self.width)

    @property
    def wavelengths(self) -> Optional[np.ndarray]:
        """The spectral bins' centres in nm, or None (render with ``spectral_bins``)."""
        s = self._native.spectral_bytes()
        return None if s is None else np.asarray(s[0], dtype=np.float32)

    @property
    def stokes(self) -> Optional[np.ndarray]:
        """A polarised render's Stokes vector as CIE X, Y, Z, shape (height, width, 4, 3): S0
        (the image's ``xyz``), S1, S2, S3 on the luminance scale (Y in cd/m²), in the camera's
        frame (S1 > 0 horizontal, S2 > 0 along the diagonal up and to the right, S3 > 0
        right-circular). None for an unpolarised render."""
        s = self._native.stokes_bytes()
        if s is None:
            return None
        s123 = self._plane(s, self.height, self.width, 3, 3)
        return np.concatenate([self.xyz[:, :, None, :], s123], axis=2)

    @property
    def dolp(self) -> Optional[np.ndarray]:
        """Degree of linear polarisation of the luminance, √(S1² + S2²)/S0 of Y
        (dimensionless, 0 where Y is 0), shape (height, width); None unpolarised."""
        s = self.stokes
        if s is None:
            return None
        y = s[:, :, :, 1].astype(np.float64)
        lin = np.hypot(y[:, :, 1], y[:, :, 2])
        return np.where(y[:, :, 0] > 0, lin / np.where(y[:, :, 0] > 0, y[:, :, 0], 1), 0.0)

    @property
    def spectral(self) -> Optional[np.ndarray]:
        """Mean spectral radiance per bin in W·m⁻²·sr⁻¹·nm⁻¹, shape (height, width, bins);
        its wavelength axis is ``wavelengths``. None without bins."""
        s = self._native.spectral_bytes()
        if s is None:
            return None
        planes = self._plane(s[1], len(s[0]), self.height, self.width)
        return np.moveaxis(planes, 0, -1)

    def mean_luminance(
        self, region: Optional[Tuple[int, int, int, int]] = None
    ) -> Tuple[float, float]:
        """The mean luminance over ``region`` = (x0, y0, width, height) (default: the whole
        image) and its standard error, both in cd/m². The error comes from each pixel's
        sample variance (NaN for the light and bdpt integrators, whose pixels have none)."""
        x0, y0, w, h = region if region is not None else (0, 0, self.width, self.height)
        return self._native.mean_luminance(x0, y0, w, h)

    def __repr__(self) -> str:
        return f"<spectrace.Image {self.width}×{self.height}, {self.spp} spp>"


def _scene(scene: Union[Scene, str, os.PathLike]) -> Scene:
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, os.PathLike):
        return Scene.load(scene)
    if isinstance(scene, str):
        # TOML text has a table or a key; anything else is a file's path
        if "\n" in scene or "=" in scene or scene.lstrip().startswith("["):
            return Scene.from_toml(scene)
        return Scene.load(scene)
    raise TypeError(f"expected a Scene, a path or TOML text, not {type(scene).__name__}")


def render(
    scene: Union[Scene, str, os.PathLike],
    spp: Optional[int] = None,
    seed: int = 0,
    integrator: Optional[str] = None,
    threads: Optional[int] = None,
    spectral_bins: Optional[int] = None,
    time_limit: Optional[float] = None,
    target_error: Optional[float] = None,
) -> Image:
    """Renders ``scene`` (a Scene, a file path, or TOML text).

    ``spp`` samples per pixel, ``integrator`` "path", "light", "bdpt" or "whitted", and
    ``spectral_bins`` default to the scene's; ``threads`` to every core (the image does not
    depend on it); ``time_limit`` in seconds and ``target_error`` (relative, of Y) stop early at
    the end of a pass (without ``spp``, a budget renders until it ends). The GIL is released;
    Ctrl-C stops the render and raises KeyboardInterrupt (from the main thread, where Python
    runs signal handlers).
    """
    s = _scene(scene)
    return Image(
        _native.render(
            s._native, spp, seed, integrator, threads, spectral_bins, time_limit, target_error
        )
    )


class MeterReading:
    """One meter point's reading: ``illuminance`` (lx) and ``irradiance`` (W/m², over the
    wavelength range), each with its standard error."""

    __slots__ = (
        "meter",
        "cell",
        "position",
        "illuminance",
        "illuminance_se",
        "irradiance",
        "irradiance_se",
    )

    def __init__(self, row: Tuple[Any, ...]) -> None:
        self.meter: str = row[0]
        self.cell: Tuple[int, int] = (row[1], row[2])
        self.position: Tuple[float, float, float] = (row[3], row[4], row[5])  # m
        self.illuminance: float = row[6]  # lx
        self.illuminance_se: float = row[7]  # lx
        self.irradiance: float = row[8]  # W/m²
        self.irradiance_se: float = row[9]  # W/m²

    def __repr__(self) -> str:
        return (
            f"<MeterReading {self.meter}{list(self.cell)}: {self.illuminance:.6g} lx "
            f"± {self.illuminance_se:.2g}>"
        )


def measure(
    scene: Union[Scene, str, os.PathLike],
    samples: int = 4096,
    seed: int = 0,
    threads: Optional[int] = None,
) -> List[MeterReading]:
    """Reads every illuminance meter (``[[sensors]]``) of the scene, as ``spectrace measure``.
    The GIL is released; Ctrl-C stops it and raises KeyboardInterrupt."""
    s = _scene(scene)
    return [MeterReading(r) for r in _native.measure(s._native, samples, seed, threads)]


class Spectrum:
    """A named spectrum's values: ``kind`` says what they are; ``values`` one per wavelength
    (for a conductor its n, with ``k`` its extinction coefficient)."""

    __slots__ = ("name", "kind", "wavelengths", "values", "k")

    def __init__(
        self, name: str, kind: str, wavelengths: np.ndarray, values: np.ndarray, k: Optional[np.ndarray]
    ) -> None:
        self.name = name
        self.kind = kind
        self.wavelengths = wavelengths  # nm
        self.values = values
        self.k = k

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        v = self.values if self.k is None else self.values + 1j * self.k
        return np.asarray(v, dtype=dtype)

    def __repr__(self) -> str:
        return f"<Spectrum {self.name}: {self.kind} at {len(self.wavelengths)} wavelengths>"


def spectrum(name: str, wavelengths: Sequence[Union[float, str]]) -> Spectrum:
    """A named spectrum (``"cie-d65"``, ``"glass:N-BK7"``, ``"metal:Au"``,
    ``"colorchecker:red"``, ``"blackbody:3200K"``) at wavelengths: numbers of nm, or strings
    with a length unit such as ``"0.55 um"`` (read as in scene files). ``np.asarray(result)`` gives the values (complex n + ik for
    conductors)."""
    ws = np.atleast_1d(np.asarray(wavelengths, dtype=object)).tolist()
    kind, nm, values, k = _native.spectrum(name, ws)
    return Spectrum(
        name,
        kind,
        np.asarray(nm, dtype=np.float64),
        np.asarray(values, dtype=np.float64),
        None if k is None else np.asarray(k, dtype=np.float64),
    )


def lens(
    path: Union[str, os.PathLike],
    wavelengths: Sequence[Union[float, str]] = (486.1327, 587.5618, 656.2725),
    spot: bool = False,
) -> Dict[str, np.ndarray]:
    """A lens file's (pbrt-v4's format, catalogue glasses allowed) first-order optics per
    wavelength, as ``spectrace lens`` prints them: arrays ``wavelength_nm``, ``efl_mm``
    (paraxial effective focal length), ``bfl_mm`` (back focal length from the last vertex) and,
    with ``spot``, ``spot_rms_um`` (RMS radius of a real axial bundle on each wavelength's
    paraxial focal plane, µm)."""
    ws = np.atleast_1d(np.asarray(wavelengths, dtype=object)).tolist()
    rows = _native.lens(os.fspath(path), ws, spot)
    out = {
        "wavelength_nm": np.array([r[0] for r in rows]),
        "efl_mm": np.array([r[1] for r in rows]),
        "bfl_mm": np.array([r[2] for r in rows]),
    }
    if spot:
        out["spot_rms_um"] = np.array([np.nan if r[3] is None else r[3] * 1e3 for r in rows])
    return out


def material_albedo(
    scene: Union[Scene, str, os.PathLike],
    material: str,
    angle_deg: float,
    wavelengths: Sequence[Union[float, str]],
    samples: int = 65536,
) -> Dict[str, np.ndarray]:
    """A material's directional-hemispherical reflectance and transmittance (fractions of the
    power arriving at ``angle_deg`` from the normal) per wavelength, as ``spectrace material``
    prints them: arrays ``wavelength_nm``, ``reflectance``, ``transmittance`` and their
    standard errors ``reflectance_se``, ``transmittance_se`` (0 for smooth materials, whose
    values are exact)."""
    s = _scene(scene)
    ws = np.atleast_1d(np.asarray(wavelengths, dtype=object)).tolist()
    rows = _native.material_albedo(s._native, material, float(angle_deg), ws, samples)
    keys = ["wavelength_nm", "reflectance", "transmittance", "reflectance_se", "transmittance_se"]
    return {k: np.array([r[i] for r in rows]) for i, k in enumerate(keys)}
