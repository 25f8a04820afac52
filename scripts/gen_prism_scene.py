#!/usr/bin/env python3
"""Writes scenes/prism.toml, the default scene: an N-SF11 prism on a table in a room, a
projector's collimated beam dispersed into a rainbow on the back wall.

The geometry is computed here so that the beam meets the prism at the minimum-deviation
incidence for the d line (587.56 nm) and leaves straight toward the back wall (-z):
N-SF11 (SCHOTT Sellmeier coefficients, as in spectra/glass/sellmeier.toml), apex 60 deg:
theta_i = asin(n_d sin 30 deg), deviation 2 theta_i - 60 deg.

With --benchmark it writes benchmarks/scenes/prism_room.toml instead: the same room at
320 x 180 with the beam replaced by a projector (a small lamp disk at the back of a black tube
aimed at the prism), so that camera paths can find the rainbow too, by hitting the lamp after
two refractions, rarely, and the camera looking at the part of the wall the rainbow covers: a
caustic-dominated scene for scripts/bench_bdpt.py.

Usage: python3 scripts/gen_prism_scene.py [--benchmark]  (standard library only)
"""
import sys
import math
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent

B = [1.73759695, 0.313747346, 1.89878101]
C = [0.013188707, 0.0623068142, 155.23629]


def n_sf11(l_nm):
    l2 = (l_nm * 1e-3) ** 2
    return math.sqrt(1 + sum(b * l2 / (l2 - c) for b, c in zip(B, C)))


BENCHMARK = "--benchmark" in sys.argv[1:]

# the room (m): x in [-2.5, 2.5], y in [0, 2.7], z in [-2.5, 2.5]
TABLE_TOP = 0.75
if BENCHMARK:
    # the benchmark keeps the default scene of issues 11-29
    SIDE = 0.16  # prism triangle side
    HEIGHT = 0.22  # prism height (its axis is vertical)
    CENTRE = (-0.2, -0.3)  # prism centroid (x, z)
else:
    # issue 30: a larger prism near the front of the room, so that the spectrum it throws on
    # the back wall, 3.9 m away, is about 70 cm long
    SIDE = 0.20
    HEIGHT = 0.30
    CENTRE = (-0.45, 0.6)

n_d = n_sf11(587.56)


def exit_angle(theta_in, l_nm):
    """Exit angle from face BC of a ray entering face AC at incidence theta_in (rad)."""
    n = n_sf11(l_nm)
    r2 = math.radians(60) - math.asin(math.sin(theta_in) / n)
    return math.asin(n * math.sin(r2))


if BENCHMARK:
    # minimum deviation for the d line
    theta_i = math.asin(n_d * 0.5)
else:
    # 4 deg under minimum deviation: the exit nears grazing for violet, which spreads the
    # spectrum 36 % wider (14.6 deg from 400 to 700 nm against 10.7 deg)
    theta_i = math.radians(59.0)
theta_e = exit_angle(theta_i, 587.56)
dev = theta_i + theta_e - math.radians(60)
spread = exit_angle(theta_i, 400) - exit_angle(theta_i, 700)
# local 2D frame (u, v): base A(-s/2, 0), B(s/2, 0), apex C(0, s sqrt3/2); the beam enters AC
# travelling at angle phi = theta_i - 30 deg, leaves BC at angle 30 deg - theta_e
phi = theta_i - math.radians(30)
# rotation alpha taking the local exit direction of the d line to world (x, z) = (0, -1)
alpha = math.radians(-90) - (math.radians(30) - theta_e)


def to_world(u, v):
    ca, sa = math.cos(alpha), math.sin(alpha)
    return (ca * u - sa * v, sa * u + ca * v)


s = SIDE
h3 = s * math.sqrt(3) / 2
local = [(-s / 2, 0), (s / 2, 0), (0, h3)]
cu, cv = 0, h3 / 3  # centroid
tri = []
for u, v in local:
    x, z = to_world(u - cu, v - cv)
    tri.append((CENTRE[0] + x, CENTRE[1] + z))
y0, y1 = TABLE_TOP, TABLE_TOP + HEIGHT
verts = [(x, y0, z) for x, z in tri] + [(x, y1, z) for x, z in tri]
centroid = (sum(v[0] for v in verts) / 6, (y0 + y1) / 2, sum(v[2] for v in verts) / 6)


def outward(f):
    a, b, c = (verts[i] for i in f)
    e1 = [b[k] - a[k] for k in range(3)]
    e2 = [c[k] - a[k] for k in range(3)]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    d = [a[k] - centroid[k] for k in range(3)]
    return f if sum(n[k] * d[k] for k in range(3)) > 0 else [f[0], f[2], f[1]]


faces = [[0, 1, 2], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]]
faces = [outward(f) for f in faces]

# the beam: aimed at the middle of face AC (local), travelling at +phi (local)
mu, mv = (local[0][0] + local[2][0]) / 2 - cu, (local[0][1] + local[2][1]) / 2 - cv
ex, ez = to_world(mu, mv)
entry = (CENTRE[0] + ex, TABLE_TOP + HEIGHT / 2, CENTRE[1] + ez)
dx, dz = to_world(math.cos(phi), math.sin(phi))
beam_from = (entry[0] - 1.0 * dx, entry[1], entry[2] - 1.0 * dz)


def v3(p):
    return "[" + ", ".join(f"{c:.5f}" for c in p) + "]"


# blocks both scenes share
MATERIALS = """[materials.sf11]
type = "dielectric"
ior = "N-SF11"

[materials.wall]
type = "diffuse"
reflectance = "colorchecker:neutral-8"

[materials.floor]
type = "diffuse"
reflectance = "colorchecker:neutral-3-5"

[materials.table]
type = "diffuse"
reflectance = "colorchecker:dark-skin"
"""
PRISM_AND_ROOM = f"""[[shapes]]
type = "mesh"
material = "sf11"
vertices = [
  {v3(verts[0])}, {v3(verts[1])}, {v3(verts[2])},
  {v3(verts[3])}, {v3(verts[4])}, {v3(verts[5])},
]
faces = {faces}

# the room: walls and ceiling (a box seen from inside), and a darker floor just above its base
[[shapes]]
type = "box"
material = "wall"
two_sided = true
transform = [{{ scale = [2.5, 1.35, 2.5] }}, {{ translate = [0, 1.35, 0] }}]

[[shapes]]
type = "rectangle"
material = "floor"
transform = [{{ scale = 2.5 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}, {{ translate = [0, 0.001, 0] }}]
"""
PANEL = """# a warm ceiling panel facing down
[[shapes]]
type = "rectangle"
transform = [{ scale = 0.5 }, { rotate = { axis = [1, 0, 0], angle = "90 deg" } }, { translate = [0.6, 2.69, 0.0] }]
emission = { spectrum = { blackbody = "3500 K" }, power = "12 W" }
"""

text = f"""# The default scene: a projector's white beam through an N-SF11 prism on a table, throwing a
# rainbow onto the back wall of a room lit by a ceiling panel. Rendered by bidirectional path
# tracing: the rainbow is light that only particles find (a collimated beam through two smooth
# refractions), the room is light that camera paths find best, and MIS joins them.
#
# Generated by scripts/gen_prism_scene.py, which places the prism (apex 60 deg, 16 cm sides,
# 22 cm tall, standing on its triangular base) so that the beam meets it at the minimum
# deviation for the d line (N-SF11: n_d = {n_d:.5f}, theta_i = {math.degrees(theta_i):.2f} deg,
# deviation {math.degrees(dev):.2f} deg) and leaves straight toward the back wall (-z), 2.2 m
# away. From 400 to 700 nm the exit direction turns by
# {math.degrees(2 * math.asin(n_sf11(400) * 0.5) - 2 * math.asin(n_sf11(700) * 0.5)):.2f} deg
# (at the same incidence, approximately), so the rainbow is about 35 cm long and as tall as the beam.

[camera]
eye = [0.45, 1.15, 0.8]
target = [-0.5, 0.8, -2.5]
fov = "50 deg"

[film]
width = 640
height = 360
spp = 12

[integrator]
type = "bdpt"
max_depth = 8
# Russian roulette from the second bounce: in a closed room lit by a lamp it saves more time
# than it costs noise (BENCHMARKS.md, issue 11)
rr_depth = 2
# the beam and the ceiling panel each start half of the light subpaths (by power the beam
# would get too few particles to draw a smooth rainbow)
light_selection = "uniform"

{MATERIALS}
{PRISM_AND_ROOM}
# the table: a 1.2 m × 0.7 m top on a block
[[shapes]]
type = "box"
material = "table"
transform = [{{ scale = [0.6, {TABLE_TOP / 2:.3f}, 0.35] }}, {{ translate = [{CENTRE[0]:.3f}, {TABLE_TOP / 2:.3f}, {CENTRE[1]:.3f}] }}]

{PANEL}
# the projector's beam, 2.5 cm in radius
[[lights]]
type = "beam"
position = {v3(beam_from)}
target = {v3(entry)}
radius = "25 mm"
spectrum = "cie-d65"
power = "0.1 W"
"""
# the projector's body: a black box 14 cm wide, 12 cm tall and 24 cm long, its front face just
# behind the slit, turned to the beam
yaw = math.degrees(math.atan2(dx, dz))
body_c = (beam_from[0] - 0.125 * dx, entry[1], beam_from[2] - 0.125 * dz)
table_x = (beam_from[0] + CENTRE[0]) / 2
table_z = (beam_from[2] + CENTRE[1]) / 2
table_half = (abs(beam_from[0] - CENTRE[0]) / 2 + 0.3, 0.35)

default_text = f"""# The default scene: a projector's white beam through a slit and an N-SF11 prism on a table,
# throwing a spectrum onto the back wall of a room lit by a ceiling panel. Rendered by
# bidirectional path tracing: the spectrum is light that only particles find (a collimated beam
# through two smooth refractions), the room is light that camera paths find best, and MIS joins
# them. Camera samples that see through the prism are split into their wavelengths
# (`dispersion = "split"`, the default), so the glass shows the room behind it in its colours.
#
# Generated by scripts/gen_prism_scene.py, which places the prism (apex 60 deg, 20 cm sides,
# 30 cm tall, standing on its triangular base) so that the beam meets it at
# {math.degrees(theta_i):.1f} deg, 4 deg under the minimum deviation of the d line, and the d
# line leaves straight toward the back wall (-z), {CENTRE[1] + 2.5:.1f} m away (N-SF11:
# n_d = {n_d:.5f}, exit {math.degrees(theta_e):.2f} deg, deviation {math.degrees(dev):.2f} deg).
# From 400 to 700 nm the exit direction turns by {math.degrees(spread):.2f} deg (violet leaves
# near grazing), so the spectrum is about {100 * (CENTRE[1] + 2.5) * math.tan(spread):.0f} cm long. The slit, 25 mm wide and 24 cm
# tall, blurs it over about two pixels of the image, so neighbouring pixels' hues differ by
# less than 15 deg where the spectrum is most compressed (its yellow).

[camera]
eye = [0.35, 1.55, 2.4]
target = [-0.95, 0.45, -2.5]
fov = "38 deg"

[film]
width = 640
height = 400
spp = 9

[integrator]
type = "bdpt"
max_depth = 8
# Russian roulette from the second bounce: in a closed room lit by a lamp it saves more time
# than it costs noise (BENCHMARKS.md, issue 11)
rr_depth = 2
# the beam and the ceiling panel each start half of the light subpaths (by power the beam
# would get too few particles to draw a smooth spectrum)
light_selection = "uniform"
# a camera sample through the prism carries every wavelength (issue 30, BENCHMARKS.md)
dispersion = "split"

{MATERIALS}
[materials.black]
type = "diffuse"
reflectance = "colorchecker:black-2"

{PRISM_AND_ROOM}
# the table under the projector and the prism
[[shapes]]
type = "box"
material = "table"
transform = [{{ scale = [{table_half[0]:.3f}, {TABLE_TOP / 2:.3f}, {table_half[1]:.3f}] }}, {{ translate = [{table_x:.3f}, {TABLE_TOP / 2:.3f}, {table_z:.3f}] }}]

# the projector's body, behind its slit
[[shapes]]
type = "box"
material = "black"
transform = [{{ scale = [0.07, 0.06, 0.12] }}, {{ rotate = {{ axis = [0, 1, 0], angle = "{yaw:.3f} deg" }} }}, {{ translate = {v3(body_c)} }}]

{PANEL}
# the projector's beam through a slit 25 mm wide and 24 cm tall
[[lights]]
type = "beam"
position = {v3(beam_from)}
target = {v3(entry)}
slit = ["25 mm", "24 cm"]
spectrum = "cie-d65"
power = "BEAM_POWER"
"""
default_text = default_text.replace("BEAM_POWER", "0.025 W")

if BENCHMARK:
    beam = text[text.index("# the projector's beam"):]
    # a projector: a 1.2 cm lamp disk facing the prism at the back of a 25 cm black square tube
    # (3 cm wide), which lets out a cone of about 7 deg half-angle onto the prism
    d3 = (dx, 0.0, dz)
    side = (-dz, 0.0, dx)
    hw, length = 0.015, 0.25
    back = beam_from
    tube = []
    for i, (a1, b1) in enumerate([(1, 1), (1, -1), (-1, -1), (-1, 1)]):
        tube.append(tuple(back[k] + side[k] * hw * a1 + (hw * b1 if k == 1 else 0.0) for k in range(3)))
    tube += [tuple(p[k] + d3[k] * length for k in range(3)) for p in tube]
    quads = [(0, 1), (1, 2), (2, 3), (3, 0)]
    tfaces = []
    for i, j in quads:
        tfaces += [[i, j, j + 4], [i, j + 4, i + 4]]
    tip = tuple(back[k] + d3[k] * 0.001 for k in range(3))
    target = tuple(back[k] + d3[k] for k in range(3))
    lamp = f"""# a projector where the beam starts: a lamp disk (1.2 cm radius, facing the prism) at the
# back of a black square tube 25 cm long and 3 cm wide
[materials.black]
type = "diffuse"
reflectance = "colorchecker:black-2"

[[shapes]]
type = "mesh"
material = "black"
two_sided = true
vertices = [{", ".join(v3(p) for p in tube)}]
faces = {tfaces}

[[shapes]]
type = "disk"
transform = [{{ scale = 0.012 }}, {{ look_at = {{ eye = {v3(tip)}, target = {v3(target)}, up = [0, 1, 0] }} }}]
emission = {{ spectrum = "cie-d65", power = "20 W" }}
"""
    text = text.replace(beam, lamp)
    # the scene's Russian roulette stays at its default for both integrators compared
    text = text.replace(
        "# Russian roulette from the second bounce: in a closed room lit by a lamp it saves more time\n"
        "# than it costs noise (BENCHMARKS.md, issue 11)\nrr_depth = 2\n",
        "",
    )
    # the view: the wall where the lamp's rainbow lands, which fills most of the image (the
    # prism and the lamp stay outside it), so that the image's error is the caustic's
    text = text.replace(
        'eye = [0.45, 1.15, 0.8]\ntarget = [-0.5, 0.8, -2.5]\nfov = "50 deg"',
        f'eye = [0.2, 1.0, 0.3]\ntarget = [{CENTRE[0]:.2f}, {TABLE_TOP + HEIGHT / 2:.2f}, -2.5]\nfov = "30 deg"',
    )
    text = text.replace("width = 640\nheight = 360", "width = 320\nheight = 180")
    text = "# Benchmark variant of scenes/prism.toml (scripts/gen_prism_scene.py --benchmark): the beam is\n# replaced by a projector's lamp, which `path` can also reach through the prism.\n#\n" + text
    (ROOT / "benchmarks" / "scenes" / "prism_room.toml").write_text(text)
else:
    (ROOT / "scenes" / "prism.toml").write_text(default_text)
print(f"n_d {n_d:.5f}, theta_i {math.degrees(theta_i):.3f} deg, deviation {math.degrees(dev):.3f} deg")
