#!/usr/bin/env python3
"""Builds the scene layouts of tests/mitsuba_structure.rs in a temporary folder and prints what
Mitsuba 3.9.1 finds in them, the truth those tests assert:

- `<path>` folders are searched latest first (the mesh found is b/tri.obj, bbox max (2, 2, 0));
- an include is found next to the including file, then by the resolver (3 emitters); a mesh
  named in an included file resolves against the scene's folder (bbox max (3, 3, 0)), and a
  `<path>` in an included file has no effect;
- a top-level area emitter with an id, referred to from a shape, makes that shape emit and is
  not an emitter of its own (1 emitter); a top-level sampler referred to from the sensor gives
  the sensor its sample_count.

Usage: pip install mitsuba==3.9.1; python3 scripts/check_mitsuba_structure.py
"""
import os
import tempfile

import mitsuba as mi

mi.set_variant("scalar_spectral")

HEAD = """<scene version="3.0.0">
  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <emitter type="constant"/>
"""


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def tri(k):
    return f"v 0 0 0\nv {k} 0 0\nv 0 {k} 0\nf 1 2 3\n"


with tempfile.TemporaryDirectory() as d:
    write(f"{d}/a/tri.obj", tri(1))
    write(f"{d}/b/tri.obj", tri(2))
    write(f"{d}/tri.obj", tri(3))
    write(f"{d}/path.xml", HEAD + """  <path value="a"/>
  <path value="b"/>
  <shape type="obj"><string name="filename" value="tri.obj"/></shape>
</scene>""")
    s = mi.load_file(f"{d}/path.xml")
    print("path: mesh bbox max", [list(sh.bbox().max) for sh in s.shapes()])

    write(f"{d}/parts/shapes.xml", """<scene version="3.0.0">
  <path value="meshes"/>
  <include filename="light.xml"/>
  <include filename="parts/light2.xml"/>
  <shape type="obj"><string name="filename" value="tri.obj"/></shape></scene>""")
    write(f"{d}/parts/light.xml", """<scene version="3.0.0"><emitter type="point">
  <point name="position" value="0, 3, 0"/></emitter></scene>""")
    write(f"{d}/parts/light2.xml", """<scene version="3.0.0"><emitter type="point">
  <point name="position" value="0, 4, 0"/></emitter></scene>""")
    write(f"{d}/parts/tri.obj", tri(1))
    write(f"{d}/parts/meshes/tri.obj", tri(2))
    write(f"{d}/include.xml", HEAD + '  <include filename="parts/shapes.xml"/>\n</scene>')
    s = mi.load_file(f"{d}/include.xml")
    print("include: emitters", len(s.emitters()),
          "mesh bbox max", [list(sh.bbox().max) for sh in s.shapes()])

    write(f"{d}/refs.xml", """<scene version="3.0.0">
  <sampler type="ldsampler" id="s"><integer name="sample_count" value="64"/></sampler>
  <emitter type="area" id="lamp"><rgb name="radiance" value="3, 3, 3"/></emitter>
  <sensor type="perspective">
    <ref id="s"/>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <shape type="sphere"><ref id="lamp"/></shape>
  <shape type="disk"/>
</scene>""")
    s = mi.load_file(f"{d}/refs.xml")
    print("refs: emitters", len(s.emitters()),
          "emitting shapes", [sh.emitter() is not None for sh in s.shapes()],
          "spp", s.sensors()[0].sampler().sample_count())
