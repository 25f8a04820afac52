#!/usr/bin/env python3
"""Mitsuba 3.9.1 (scalar_spectral) numbers for the importer's defaults:
tests/data/mitsuba_defaults.toml, read by tests/mitsuba_defaults.rs.

Usage: pip install mitsuba==3.9.1 && python3 scripts/gen_mitsuba_defaults.py

What it records, all from Mitsuba itself (nothing is computed by spectrace):
- [[fov]]: the sensor's horizontal field of view (the sensor's `x_fov` parameter, `mi.traverse`) for film
  sizes and fov / fov_axis / focal_length combinations, including none (50 mm default);
- [[emitter]]: the mean X, Y, Z of a 16 × 16 render (box filter, XYZ film) of a `constant`
  environment whose radiance is the given XML element (or absent), and its standard error
  from the spread of the per-pixel means; the environment is all the camera sees, so every
  pixel's expectation is the radiance's XYZ on Mitsuba's film scale;
- [[max_depth]]: a 16 × 16 render of a ρ = 0.5 diffuse rectangle filling the middle of the
  view, lit by a constant environment of radiance 1 (uniform spectrum), for max_depth 1, 2, 3:
  the mean Y of the central 4 × 4 pixels (wholly on the rectangle) and of the 2 × 2 corner
  blocks top-left and bottom-right (wholly environment);
- [[point]]: the position of a `point` emitter placed by a `to_world` (its to_string).
"""
import re

import numpy as np
import mitsuba as mi

assert mi.__version__ == "3.9.1", mi.__version__
mi.set_variant("scalar_spectral")
ROOT = __import__("pathlib").Path(__file__).resolve().parent.parent
OUT = ROOT / "tests" / "data" / "mitsuba_defaults.toml"

SENSOR = """<scene version="3.0.0">
  <sensor type="perspective">{extra}
    <film type="hdrfilm"><integer name="width" value="{w}"/><integer name="height" value="{h}"/></film>
  </sensor>
</scene>"""


def x_fov(xml):
    s = mi.load_string(xml).sensors()[0]
    return float(mi.traverse(s)["x_fov"])


ENV = """<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="{depth}"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, -3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
    <film type="hdrfilm">
      <integer name="width" value="16"/><integer name="height" value="16"/>
      <rfilter type="box"/><string name="pixel_format" value="xyz"/>
    </film>
  </sensor>
  <emitter type="constant">{radiance}</emitter>{shapes}
</scene>"""

RECT = """
  <shape type="rectangle">
    <transform name="to_world"><scale value="0.5"/><rotate y="1" angle="180"/></transform>
    <bsdf type="diffuse"><spectrum name="reflectance" value="0.5"/></bsdf>
  </shape>"""


def render(xml, spp):
    img = np.array(mi.render(mi.load_string(xml), seed=1, spp=spp), dtype=np.float64)
    px = img.reshape(-1, 3)
    return px.mean(axis=0), px.std(axis=0, ddof=1) / np.sqrt(len(px))


def q(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


lines = ["# Written by scripts/gen_mitsuba_defaults.py from Mitsuba 3.9.1 scalar_spectral; do not edit.", ""]

fov_cases = []
for w, h in [(32, 32), (48, 32), (32, 48)]:
    fov_cases += [
        (w, h, ""),
        (w, h, '<string name="focal_length" value="35mm"/>'),
        (w, h, '<string name="focal_length" value="85"/>'),
        (w, h, '<float name="fov" value="40"/>'),
        (w, h, '<float name="fov" value="40"/><string name="fov_axis" value="y"/>'),
        (w, h, '<float name="fov" value="40"/><string name="fov_axis" value="smaller"/>'),
        (w, h, '<float name="fov" value="40"/><string name="fov_axis" value="larger"/>'),
        (w, h, '<float name="fov" value="40"/><string name="fov_axis" value="diagonal"/>'),
    ]
for w, h, extra in fov_cases:
    xml = SENSOR.format(extra=extra, w=w, h=h)
    lines += ["[[fov]]", f"width = {w}", f"height = {h}", f"xml = {q(extra)}", f"x_fov = {x_fov(xml)!r}", ""]

SPP = 4096
for radiance in [
    "",
    '<float name="radiance" value="2"/>',
    '<spectrum name="radiance" value="2"/>',
    '<spectrum name="radiance" type="d65"/>',
    '<spectrum name="radiance" type="d65"><float name="scale" value="3"/></spectrum>',
    '<rgb name="radiance" value="1, 1, 1"/>',
    '<rgb name="radiance" value="0.2, 0.5, 0.8"/>',
    '<rgb name="radiance" value="3, 1.5, 0.4"/>',
]:
    (m, se) = render(ENV.format(depth=-1, spp=SPP, radiance=radiance, shapes=""), SPP)
    lines += ["[[emitter]]", f"xml = {q(radiance)}", f"spp = {SPP}",
              f"xyz = [{float(m[0])!r}, {float(m[1])!r}, {float(m[2])!r}]", f"stderr = [{float(se[0])!r}, {float(se[1])!r}, {float(se[2])!r}]", ""]
    print(radiance, m, se)

for depth in [1, 2, 3]:
    xml = ENV.format(depth=depth, spp=SPP, radiance='<spectrum name="radiance" value="1"/>', shapes=RECT)
    img = np.array(mi.render(mi.load_string(xml), seed=1, spp=SPP), dtype=np.float64)[..., 1]
    centre = img[6:10, 6:10].mean()  # pixels wholly on the rectangle
    corner = np.concatenate([img[:2, :2].ravel(), img[-2:, -2:].ravel()]).mean()  # wholly environment
    lines += ["[[max_depth]]", f"max_depth = {depth}", f"spp = {SPP}",
              f"y_centre = {float(centre)!r}", f"y_corner = {float(corner)!r}", ""]
    print(depth, centre, corner)

for tr in ['<translate x="1" y="2" z="3"/><rotate y="1" angle="30"/><scale value="2"/>',
           '<rotate y="1" angle="90"/><translate x="1" y="2" z="3"/>',
           '<lookat origin="1, 2, 3" target="0, 0, 0" up="0, 1, 0"/>']:
    xml = f'<scene version="3.0.0"><emitter type="point"><transform name="to_world">{tr}</transform></emitter></scene>'
    e = mi.load_string(xml).emitters()[0]
    p = [float(v) for v in re.search(r"position = \[([^\]]*)\]", str(e)).group(1).split(",")]
    lines += ["[[point]]", f"transform = {q(tr)}", f"position = {p!r}", ""]

OUT.write_text("\n".join(lines))
print("wrote", OUT)
