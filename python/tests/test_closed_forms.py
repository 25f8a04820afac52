"""spectrace from Python against closed forms, CIE values and catalogue glass data.

Run with `python/test.sh` (builds the wheel in a fresh virtual environment first).
"""

import math
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import spectrace


def point_over_plane(flux="800 lm", height=2.0, rho=0.18):
    """A grey floor under a point light, seen straight down through a 2° view."""
    return (
        spectrace.Scene.builder()
        .camera(eye=[0, 1, 0], target=[0, 0, 0], up=[0, 0, 1], fov="2 deg")
        .film(16, 16)
        .material("grey", type="diffuse", reflectance=rho)
        .shape(
            "rectangle",
            material="grey",
            transform=[{"scale": 10}, {"rotate": {"axis": [1, 0, 0], "angle": "-90 deg"}}],
        )
        .light("point", position=[0, height, 0], power=flux, spectrum="cie-a")
        .build()
    )


def test_point_light_over_plane():
    # L = ρ·E/π with E = Φ/(4π h²) below the light (cos³θ within 1.1e-4 over the view)
    image = spectrace.render(point_over_plane(), spp=64)
    value, se = image.mean_luminance()
    expected = 0.18 * 800.0 / (4.0 * math.pi**2 * 2.0**2)
    assert abs(value - expected) < 3.0 * se + 0.002 * expected, (value, se, expected)
    assert image.luminance.shape == (16, 16)
    assert image.luminance.dtype == np.float32
    # the region's mean is the mean of the array
    assert abs(float(image.luminance.mean(dtype=np.float64)) - value) < 1e-6 * value


def test_malus_law_through_two_polarisers():
    # unpolarised light of 1 W·m⁻²·sr⁻¹ through ideal polarisers at 0° and 60°: ½cos²60° = 1/8
    # of the light, fully linearly polarised; an unpolarised render has no Stokes vector
    toml = textwrap.dedent(
        """
        [camera]
        type = "orthographic"
        eye = [0, 0, 0]
        target = [0, 0, 1]
        view_width = 0.5
        [film]
        width = 4
        height = 4
        [materials.p0]
        type = "polariser"
        [materials.p1]
        type = "polariser"
        angle = "60 deg"
        [[shapes]]
        type = "rectangle"
        material = "p0"
        transform = [{ translate = [0, 0, 1] }]
        [[shapes]]
        type = "rectangle"
        material = "p1"
        transform = [{ translate = [0, 0, 2] }]
        [[lights]]
        type = "environment"
        radiance = "1 W/m^2/sr"
        """
    )
    image = spectrace.render(toml, spp=1024)
    assert abs(float(image.radiance.mean(dtype=np.float64)) - 0.125) < 0.125 * 2e-3
    assert image.stokes.shape == (4, 4, 4, 3)
    assert np.allclose(image.stokes[:, :, 0, :], image.xyz)
    assert np.all(np.abs(image.dolp - 1.0) < 1e-4)
    clear_toml = toml.replace('type = "polariser"', 'type = "null"').replace('angle = "60 deg"', "")
    clear = spectrace.render(clear_toml, spp=16)
    assert clear.stokes is None and clear.dolp is None


def test_luminance_calibration():
    # inside a black sphere that emits 100 cd/m² of D65 every pixel sees 100 cd/m²,
    # with D65's chromaticity (CIE 15: x = 0.31272, y = 0.32903)
    toml = textwrap.dedent(
        """
        [camera]
        eye = [0, 0, 0]
        target = [0, 0, 1]
        fov = "40 deg"
        [film]
        width = 8
        height = 8
        [materials.black]
        type = "diffuse"
        reflectance = 0
        [[shapes]]
        type = "sphere"
        radius = 1
        material = "black"
        two_sided = true
        emission = { spectrum = "cie-d65", luminance = "100 cd/m^2", two_sided = true }
        """
    )
    image = spectrace.render(toml, spp=64)
    value, se = image.mean_luminance()
    assert 0 < se < 1.0
    assert abs(value - 100.0) < 4.0 * se, (value, se)
    xyz = image.xyz.reshape(-1, 3).astype(np.float64).sum(axis=0)
    x, y = xyz[0] / xyz.sum(), xyz[1] / xyz.sum()
    assert abs(x - 0.31272) < 0.002 and abs(y - 0.32903) < 0.002, (x, y)
    assert image.metadata["spectrace:samplesPerPixel"] == "64"
    assert "cd/m^2" in image.metadata["spectrace:units"]
    assert image.complete and image.stop_reason == "complete"


def test_target_error_budget():
    # a budget without spp renders until the estimated relative error of Y is below it
    image = spectrace.render(point_over_plane(), target_error=0.01)
    assert image.stop_reason == "target error" and not image.complete
    value, se = image.mean_luminance()
    assert se / value < 0.01


def test_furnace_spectral_radiance():
    # a closed ρ = 0.5 sphere emitting 1 W/m²/sr equal-energy over 360–830 nm:
    # L = Le/(1 − ρ) = 2 W/m²/sr in all, 2/470 W/m²/sr/nm at every wavelength
    toml = textwrap.dedent(
        """
        [camera]
        eye = [0, 0, 0]
        target = [0, 0, 1]
        fov = "90 deg"
        [film]
        width = 16
        height = 16
        [integrator]
        type = "path"
        max_depth = 1000
        [materials.m]
        type = "diffuse"
        reflectance = 0.5
        [[shapes]]
        type = "sphere"
        radius = 1
        material = "m"
        two_sided = true
        emission = { radiance = "1 W/m^2/sr", two_sided = true }
        """
    )
    # 5 bins of 94 nm: about 52 000 wavelength samples each, a relative noise near 0.3 %
    image = spectrace.render(toml, spp=256, spectral_bins=5)
    assert image.spectral.shape == (16, 16, 5)
    assert image.wavelengths[0] == pytest.approx(407.0)
    assert abs(float(image.radiance.mean(dtype=np.float64)) / 2.0 - 1.0) < 0.01
    per_bin = image.spectral.reshape(-1, 5).astype(np.float64).mean(axis=0)
    assert np.all(np.abs(per_bin / (2.0 / 470.0) - 1.0) < 0.015), per_bin


def test_spectrum_lookups():
    # N-BK7 against Schott's Sellmeier coefficients (λ in µm)
    B = (1.03961212, 0.231792344, 1.01046945)
    C = (0.00600069867, 0.0200179144, 103.560653)
    lam = [486.1, 587.6, 656.3]
    n = spectrace.spectrum("glass:N-BK7", lam)
    for l_nm, got in zip(lam, np.asarray(n)):
        l2 = (l_nm / 1000.0) ** 2
        want = math.sqrt(1 + sum(b * l2 / (l2 - c) for b, c in zip(B, C)))
        assert abs(got - want) < 2e-5, (l_nm, got, want)
    assert n.kind == "refractive index n"
    gold = spectrace.spectrum("metal:Au", ["0.55 um"])
    assert gold.wavelengths[0] == pytest.approx(550.0)
    assert np.iscomplexobj(np.asarray(gold)) and gold.k[0] > 1.0
    with pytest.raises(ValueError, match="wavelength"):
        spectrace.spectrum("cie-d65", ["550 W"])
    d65 = spectrace.spectrum("cie-d65", [560.0])
    assert abs(d65.values[0] - 100.0) < 1e-3  # CIE: 100 at 560 nm
    with pytest.raises(spectrace.SpectraceError, match="cie-d65"):
        spectrace.spectrum("cie-d56", [500.0])


def test_errors_name_the_field():
    builder = (
        spectrace.Scene.builder()
        .camera(eye=[0, 1, 0], target=[0, 0, 0], up=[0, 0, 1], fov="2 deg")
        .material("grey", type="diffuse", reflectance=0.18)
        .shape("sphere", radius=1, material="grey")
        .light("point", position=[0, 2, 0], power="100 nm")
    )
    with pytest.raises(spectrace.SpectraceError, match=r"lights\[0\]\.power.*length") as e:
        builder.build()
    assert e.value.field == "lights[0].power" and e.value.file == "scene builder"
    text = builder.to_toml().splitlines()
    assert "100 nm" in text[e.value.line - 1], (e.value.line, text)
    with pytest.raises(spectrace.SpectraceError, match="no_such.toml"):
        spectrace.render("no_such.toml")
    with pytest.raises(spectrace.SpectraceError, match="scenes/cornel"):
        spectrace.render("scenes/cornel")
    with pytest.raises(ValueError, match="holds itself"):
        loop = []
        loop.append(loop)
        spectrace.Scene.builder().light("point", position=loop).build()
    with pytest.raises(ValueError, match="bytes"):
        spectrace.Scene.builder().shape("obj", file=b"mesh.obj").build()
    with pytest.raises(ValueError, match="time_limit"):
        spectrace.render(point_over_plane(), time_limit=1e300)
    with pytest.raises(spectrace.SpectraceError, match="target_error"):
        spectrace.render(point_over_plane(), target_error=2.0)
    with pytest.raises(ValueError, match="integrator"):
        spectrace.render(point_over_plane(), spp=1, integrator="photon")
    with pytest.raises(spectrace.SpectraceError, match="spp must be at least 1") as e:
        spectrace.render(point_over_plane(), spp=0)
    assert e.value.field is None and e.value.line is None
    with pytest.raises(spectrace.SpectraceError, match="threads must be at least 1"):
        spectrace.render(point_over_plane(), spp=1, threads=0)
    image = spectrace.render(point_over_plane(), spp=1)
    with pytest.raises(ValueError, match="leaves"):
        image.mean_luminance((10, 10, 10, 10))


def test_meter_reads_illuminance():
    # 1000 lx of parallel light from above plus a 100 cd/m² uniform sky: 1000 + 100π lx
    scene = (
        spectrace.Scene.builder()
        .camera(eye=[0, 1, -1], target=[0, 0, 0], fov="30 deg")
        .light("directional", direction=[0, -1, 0], irradiance="1000 lx")
        .light("environment", luminance="100 cd/m^2")
        .meter("point", name="up", position=[0, 0, 0], normal=[0, 1, 0])
        .build()
    )
    (r,) = spectrace.measure(scene, samples=1024)
    assert r.meter == "up"
    assert abs(r.illuminance - (1000 + 100 * math.pi)) < 4 * r.illuminance_se + 0.5, r


def test_render_releases_the_gil():
    scene = point_over_plane()
    ticks = 0
    done = threading.Event()

    def work():
        spectrace.render(scene, spp=4096, threads=1)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    t.join()
    assert ticks > 20, ticks


def test_ctrl_c_stops_the_render():
    # a render of minutes, interrupted after 2 s: KeyboardInterrupt within seconds
    code = textwrap.dedent(
        """
        import sys, spectrace
        scene = (spectrace.Scene.builder()
                 .camera(eye=[0, 1, 0], target=[0, 0, 0], up=[0, 0, 1], fov="60 deg")
                 .film(256, 256)
                 .material("grey", type="diffuse", reflectance=0.5)
                 .shape("sphere", radius=0.5, material="grey")
                 .light("environment", luminance="1 cd/m^2")
                 .build())
        print("rendering", flush=True)
        try:
            spectrace.render(scene, spp=100000)
        except KeyboardInterrupt:
            print("interrupted", flush=True)
            sys.exit(7)
        """
    )
    p = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, text=True
    )
    assert p.stdout.readline().strip() == "rendering"
    time.sleep(2.0)
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, _ = p.communicate(timeout=30)
    finally:
        p.kill()
    assert p.returncode == 7, (p.returncode, out)
    assert "interrupted" in out
    assert time.monotonic() - t0 < 10


def test_lens_focal_lengths_are_the_thick_lens_formula(tmp_path):
    # an equiconvex N-BK7 singlet: 1/f = (n−1)(2/R − (n−1)d/(n R²)), with SCHOTT's Sellmeier
    # coefficients for n at each wavelength
    f = tmp_path / "singlet.lens"
    f.write_text("0 2 0 10\n51.68 6 N-BK7 25.4\n-51.68 95 1 25.4\n")
    out = spectrace.lens(f, [486.1327, 587.5618, 656.2725], spot=True)
    b = [1.03961212, 0.231792344, 1.01046945]
    c = [0.00600069867, 0.0200179144, 103.560653]
    for l, efl in zip(out["wavelength_nm"], out["efl_mm"]):
        l2 = (l * 1e-3) ** 2
        n = math.sqrt(1 + sum(bi * l2 / (l2 - ci) for bi, ci in zip(b, c)))
        r, d = 51.68, 6.0
        expect = 1 / ((n - 1) * (2 / r - (n - 1) * d / (n * r * r)))
        assert abs(efl - expect) < 1e-6 * expect
    assert np.all(out["spot_rms_um"] > 0)


def test_material_albedo_is_fresnel_for_smooth_glass():
    scene = (
        spectrace.Scene.builder()
        .camera(eye=[0, 0, -1], target=[0, 0, 0], fov="40 deg")
        .film(4, 4)
        .material("glass", type="dielectric", ior=1.5)
        .shape("sphere", center=[0, 0, 1], radius=0.5, material="glass")
        .light("environment", luminance="1 cd/m^2")
        .build()
    )
    out = spectrace.material_albedo(scene, "glass", 0.0, [450, 550, 650])
    assert np.allclose(out["reflectance"], 0.04, atol=1e-6)
    assert np.allclose(out["transmittance"], 0.96, atol=1e-6)
    assert np.all(out["reflectance_se"] == 0)
