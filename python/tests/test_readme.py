"""The README's ten-line Python test (section "Python"), verbatim, and a check that the README
still shows exactly this code."""

import pathlib

# README begin
import math, spectrace

def test_grey_floor_under_an_800_lm_lamp():
    scene = (spectrace.Scene.builder()
             .camera(eye=[0, 1, 0], target=[0, 0, 0], up=[0, 0, 1], fov="2 deg")
             .film(16, 16)
             .material("grey", type="diffuse", reflectance=0.18)
             .shape("rectangle", material="grey", transform=[{"scale": 10}, {"rotate": {"axis": [1, 0, 0], "angle": "-90 deg"}}])
             .light("point", position=[0, 2, 0], power="800 lm", spectrum="cie-a")
             .build())
    value, se = spectrace.render(scene, spp=64).mean_luminance()  # cd/m² and its standard error
    expected = 0.18 * 800 / (4 * math.pi**2 * 2**2)                # L = ρΦ/(4π²h²)
    print(f"{value:.5f} ± {se:.5f} cd/m², closed form {expected:.5f}")
    assert abs(value - expected) < 3 * se
# README end


def test_the_readme_shows_this_test():
    me = pathlib.Path(__file__).read_text(encoding="utf-8")
    code = me.split("# README begin\n")[1].split("# README end")[0]
    readme = pathlib.Path(__file__).resolve().parents[2] / "README.md"
    assert code in readme.read_text(encoding="utf-8"), "README.md's Python example differs"
