#!/usr/bin/env python3
"""Writes tests/data/pbrt_refs.toml: numbers pbrt-v4 itself renders for small pbrt-v4 scenes,
which tests/pbrt_import.rs holds spectrace's pbrt-v4 reader to.

Each [[case]] is a scene (16 × 16 pixels, `zsobol`, the default Gaussian filter) and the mean
R, G, B and Y = 0.2126 R + 0.7152 G + 0.0722 B over the image of two renders with seeds 1 and
2 (pbrt-v4's film: Y = ∫ȳ·L dλ), with the standard error of the mean Y (the standard deviation
of the per-pixel difference of the seeds / 2 / √pixels); and the same over the object's pixels
(`object`, row-major indices: those more than 2 % off the corners' median, the sky's value
where there is one).

Usage: build pbrt-v4 with ../shared/tools/pbrt/build_pbrt.sh (it lands in
~/.cache/pbrt-v4/bin/pbrt, or set PBRT), pip install numpy OpenImageIO;
python3 scripts/gen_pbrt_refs.py
"""
import os
import shutil
import subprocess
import tempfile

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PBRT = os.environ.get("PBRT", os.path.expanduser("~/.cache/pbrt-v4/bin/pbrt"))
SPP = int(os.environ.get("SPP", "256"))

HEAD = f"""LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [30]
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Sampler "zsobol" "integer pixelsamples" {SPP}
"""
SKY = 'LightSource "infinite" "blackbody L" 5000 "float scale" 2\n'
SUN = 'LightSource "distant" "point3 from" [2 3 4] "point3 to" [0 0 0] "blackbody L" 5500 "float scale" 3\n'

CASES = [
    # metals by pbrt-v4's names, smooth and rough, under a uniform sky
    ("gold_rough", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY
     + 'Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" '
       '"float roughness" 0.05\nShape "sphere" "float radius" 1\n'),
    ("copper_default", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY
     + 'Material "conductor"\nShape "sphere" "float radius" 1\n'),
    # a named glass (dispersive) sphere in front of a lit diffuse wall
    ("bk7_sphere", HEAD + 'Integrator "path" "integer maxdepth" 8\nWorldBegin\n'
     + 'LightSource "distant" "point3 from" [1 2 3] "point3 to" [0 0 0] "blackbody L" 4000 "float scale" 3\n'
     + 'LightSource "infinite" "rgb L" [0.2 0.3 0.5]\n'
     + 'AttributeBegin\nMaterial "diffuse" "rgb reflectance" [0.7 0.6 0.3]\nTranslate 0 0 -2\n'
       'Shape "trianglemesh" "point3 P" [-4 -4 0  4 -4 0  4 4 0  -4 4 0] "integer indices" [0 1 2 0 2 3]\n'
       'AttributeEnd\n'
     + 'Material "dielectric" "spectrum eta" "glass-BK7"\nShape "sphere" "float radius" 1\n'),
    # a box lit by a two-sided area light and a point light, diffuse walls (interreflection)
    ("box_lights", HEAD + 'Integrator "path" "integer maxdepth" 6\nWorldBegin\n'
     + 'LightSource "point" "point3 from" [0.5 0.8 1] "spectrum I" [400 1 500 2 600 3 700 2] "float scale" 4\n'
     + 'AttributeBegin\nAreaLightSource "diffuse" "blackbody L" 6500 "float scale" 5 "bool twosided" true\n'
       'Translate 0 1.9 0\nRotate 90 1 0 0\nShape "disk" "float radius" 0.5\nAttributeEnd\n'
     + 'Material "diffuse" "spectrum reflectance" [400 0.3 550 0.6 700 0.8]\n'
       'Shape "trianglemesh" "point3 P" [-2 -2 -2  2 -2 -2  2 2 -2  -2 2 -2  -2 -2 2  2 -2 2  2 2 2  -2 2 2]\n'
       '  "integer indices" [0 1 2 0 2 3  0 4 5 0 5 1  3 2 6 3 6 7  0 3 7 0 7 4  1 5 6 1 6 2]\n'
     + 'AttributeBegin\nMaterial "diffuse" "blackbody reflectance" 3000\nRotate 60 1 0 0\n'
       'Shape "cylinder" "float radius" 0.4 "float zmin" -0.8 "float zmax" 0.6\nAttributeEnd\n'),
    # the same box with pbrt-v4's bidirectional path tracer
    ("box_lights_bdpt", HEAD + 'Integrator "bdpt" "integer maxdepth" 6\nWorldBegin\n'
     + 'LightSource "point" "point3 from" [0.5 0.8 1] "spectrum I" [400 1 500 2 600 3 700 2] "float scale" 4\n'
     + 'AttributeBegin\nAreaLightSource "diffuse" "blackbody L" 6500 "float scale" 5 "bool twosided" true\n'
       'Translate 0 1.9 0\nRotate 90 1 0 0\nShape "disk" "float radius" 0.5\nAttributeEnd\n'
     + 'Material "diffuse" "spectrum reflectance" [400 0.3 550 0.6 700 0.8]\n'
       'Shape "trianglemesh" "point3 P" [-2 -2 -2  2 -2 -2  2 2 -2  -2 2 -2  -2 -2 2  2 -2 2  2 2 2  -2 2 2]\n'
       '  "integer indices" [0 1 2 0 2 3  0 4 5 0 5 1  3 2 6 3 6 7  0 3 7 0 7 4  1 5 6 1 6 2]\n'
     + 'AttributeBegin\nMaterial "diffuse" "blackbody reflectance" 3000\nRotate 60 1 0 0\n'
       'Shape "cylinder" "float radius" 0.4 "float zmin" -0.8 "float zmax" 0.6\nAttributeEnd\n'),
    # pbrt-v4's photometric amounts: a point light's `power`, a distant light's and a uniform
    # sky's `illuminance`, over a diffuse floor seen from above
    ("photometric", """LookAt 0 6 0.5  0 0 0  0 0 1
Camera "perspective" "float fov" [60]
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Sampler "zsobol" "integer pixelsamples" 256
Integrator "path" "integer maxdepth" 3
WorldBegin
LightSource "point" "point3 from" [1 2 0] "blackbody I" 3000 "float power" 40
LightSource "distant" "point3 from" [1 3 2] "point3 to" [0 0 0] "rgb L" [0.9 0.7 0.4] "float illuminance" 2
LightSource "infinite" "blackbody L" 9000 "float illuminance" 0.6
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-3 0 -3  3 0 -3  3 0 3  -3 0 3] "integer indices" [0 2 1 0 3 2]
"""),
    # pbrt-v4's layered materials (its stochastic LayeredBxDF). A rough coating is lit by the
    # sky alone: pbrt-v4 lights a uniform sky by BSDF sampling only, where its layered BSDF is
    # unbiased; its f() (next-event estimation, as for the sun) is not (README, "pbrt-v4
    # scenes"; scripts/pbrt_ab.py measures it)
    ("coated_diffuse_default", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY + SUN
     + 'Material "coateddiffuse"\nShape "sphere" "float radius" 1\n'),
    ("coated_diffuse_scattering", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY
     + 'Material "coateddiffuse" "rgb reflectance" [0.2 0.5 0.8] "float roughness" 0.1 '
       '"rgb albedo" [0.9 0.6 0.3] "float g" 0.4 "float thickness" 0.3 "float eta" 1.4\n'
       'Shape "sphere" "float radius" 1\n'),
    ("coated_gold", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY
     + 'Material "coatedconductor" "float interface.roughness" 0.05 "spectrum conductor.eta" "metal-Au-eta" '
       '"spectrum conductor.k" "metal-Au-k" "float conductor.roughness" 0.2\n'
       'Shape "sphere" "float radius" 1\n'),
    ("coated_conductor_reflectance", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY + SUN
     + 'Material "coatedconductor" "rgb reflectance" [0.9 0.4 0.2] "spectrum interface.eta" "glass-BK7" '
       '"float thickness" 0.05 "integer maxdepth" 4 "integer nsamples" 2\n'
       'Shape "sphere" "float radius" 1\n'),
    # pbrt-v4's spot light with its `power` (smoothstep falloff over conedeltaangle) on a floor
    ("spot_power", """LookAt 0 6 0.5  0 0 0  0 0 1
Camera "perspective" "float fov" [60]
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Sampler "zsobol" "integer pixelsamples" SPP
Integrator "path" "integer maxdepth" 3
WorldBegin
LightSource "spot" "point3 from" [0.5 3 0.2] "point3 to" [0 0 0] "float coneangle" 25 "float conedeltaangle" 10 "blackbody I" 3200 "float power" 30
Material "diffuse" "rgb reflectance" [0.6 0.5 0.4]
Shape "trianglemesh" "point3 P" [-3 0 -3  3 0 -3  3 0 3  -3 0 3] "integer indices" [0 2 1 0 3 2]
""".replace("SPP", str(SPP))),
    # area lights' `power` as pbrt-v4 spreads it: over a sphere's and a disk's object-space
    # area, and over each triangle of a mesh (each triangle emits the whole power)
    ("area_power", """LookAt 0 6 0.5  0 0 0  0 0 1
Camera "perspective" "float fov" [60]
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Sampler "zsobol" "integer pixelsamples" SPP
Integrator "path" "integer maxdepth" 3
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "blackbody L" 4000 "float power" 20
Translate -1.5 1.5 0
Shape "sphere" "float radius" 0.3
AttributeEnd
AttributeBegin
AreaLightSource "diffuse" "rgb L" [0.3 0.6 0.9] "float power" 8 "bool twosided" true
Translate 1.5 2 0
Rotate 90 1 0 0
Shape "disk" "float radius" 0.4
AttributeEnd
AttributeBegin
AreaLightSource "diffuse" "blackbody L" 6500 "float power" 5 "float scale" 2
Shape "trianglemesh" "point3 P" [-0.5 2.5 -1.5  -0.5 2.5 -0.5  0.5 2.5 -0.5  0.5 2.5 -1.5] "integer indices" [0 2 1 0 3 2]
AttributeEnd
Material "diffuse" "rgb reflectance" [0.6 0.6 0.6]
Shape "trianglemesh" "point3 P" [-3 0 -3  3 0 -3  3 0 3  -3 0 3] "integer indices" [0 2 1 0 3 2]
""".replace("SPP", str(SPP))),
    # a BK7 prism (pbrt-v4's named glass, dispersive) on a floor under a sky and a sun
    ("bk7_prism", HEAD + 'Integrator "path" "integer maxdepth" 10\nWorldBegin\n' + SKY + SUN
     + 'Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]\n'
       'Shape "trianglemesh" "point3 P" [-4 -1 -4  4 -1 -4  4 -1 4  -4 -1 4] "integer indices" [0 1 2 0 2 3]\n'
     + 'AttributeBegin\nRotate 20 0 1 0\nMaterial "dielectric" "spectrum eta" "glass-BK7"\n'
       'Shape "trianglemesh" "point3 P" [-1 -1 0.6  1 -1 0.6  0 0.7 0.6  -1 -1 -0.6  1 -1 -0.6  0 0.7 -0.6]\n'
       '  "integer indices" [0 1 2  3 5 4  0 3 4  0 4 1  1 4 5  1 5 2  2 5 3  2 3 0]\nAttributeEnd\n'),
    # pbrt-v4's image infinite light: an equal-area octahedral map (tests/data/pbrt/eqarea.exr,
    # written here), rotated, over a gold sphere and a diffuse floor
    ("gold_equal_area", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n'
     + 'AttributeBegin\nRotate -90 1 0 0\nRotate 30 0 0 1\nLightSource "infinite" "string filename" "eqarea.exr" "float scale" 1.5\nAttributeEnd\n'
     + 'Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]\n'
       'Shape "trianglemesh" "point3 P" [-4 -1 -4  4 -1 -4  4 -1 4  -4 -1 4] "integer indices" [0 1 2 0 2 3]\n'
     + 'Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" 0.02\n'
       'Shape "sphere" "float radius" 0.8\n'),
    # a mix (pbrt-v4 picks one material per hit; its expectation is the blend) and a thin
    # dielectric sheet before it
    ("mix_thin", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY + SUN
     + 'MakeNamedMaterial "red" "string type" "diffuse" "rgb reflectance" [0.8 0.2 0.1]\n'
       'MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" 0.1\n'
       'Material "mix" "string materials" ["red" "gold"] "float amount" 0.3\nShape "sphere" "float radius" 1\n'
       'Material "thindielectric" "float eta" 1.7\n'
       'Shape "trianglemesh" "point3 P" [-1.2 -1.2 1.5  1.2 -1.2 1.5  1.2 0 1.5  -1.2 0 1.5] "integer indices" [0 1 2 0 2 3]\n'),
    # Loop subdivision surfaces: a closed tetrahedron (interior rules) and an open pyramid
    # (boundary rules), shaded by their limit normals
    ("loop_subdiv", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY
     + 'AttributeBegin\nTranslate -0.6 0.1 0\nRotate 30 0 1 0\nScale 1.1 1.1 1.1\n'
       'Material "coateddiffuse" "rgb reflectance" [0.7 0.3 0.2] "float roughness" 0.05\n'
       'Shape "loopsubdiv" "integer levels" 3 "point3 P" [1 1 1  -1 -1 1  -1 1 -1  1 -1 -1]\n'
       '  "integer indices" [0 1 2  0 3 1  0 2 3  1 3 2]\nAttributeEnd\n'
       'AttributeBegin\nTranslate 0.65 -0.5 0\nRotate -70 1 0 0\nScale 0.8 0.8 0.8\n'
       'Material "conductor" "spectrum eta" "metal-Ag-eta" "spectrum k" "metal-Ag-k" "float roughness" 0.01\n'
       'Shape "loopsubdiv" "integer levels" 2 "point3 P" [-1 -1 0  1 -1 0  1 1 0  -1 1 0  0 0 1.2]\n'
       '  "integer indices" [0 1 4  1 2 4  2 3 4  3 0 4]\nAttributeEnd\n'),
    # bilinear patches: a rectangular light with `power` (pbrt-v4 spreads it over each patch),
    # a twisted (non-planar) patch and a floor of two patches
    ("bilinear", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY
     + 'AttributeBegin\nAreaLightSource "diffuse" "blackbody L" 5000 "float power" 6\n'
       'Shape "bilinearmesh" "point3 P" [-0.6 1.6 -0.4  0.6 1.6 -0.4  -0.6 1.6 0.6  0.6 1.6 0.6]\nAttributeEnd\n'
     + 'Material "diffuse" "rgb reflectance" [0.6 0.5 0.4]\n'
       'Shape "bilinearmesh" "point3 P" [-3 -1 -3  0 -1 -3  3 -1 -3  -3 -1 3  0 -1 3  3 -1 3]\n'
       '  "integer indices" [0 1 3 4  1 2 4 5]\n'
     + 'Material "coateddiffuse" "rgb reflectance" [0.2 0.6 0.3] "float roughness" 0.1\n'
       'Shape "bilinearmesh" "point3 P" [-1 -0.5 -0.5  1 -0.5 0.5  -1 0.8 0.5  1 0.8 -0.5]\n'),
    # pbrt-v4's diffuse transmitter: a lampshade (an open cylinder) around a spherical light,
    # over a floor
    ("diffuse_transmission", HEAD + 'Integrator "path" "integer maxdepth" 6\nWorldBegin\n'
     + 'AttributeBegin\nAreaLightSource "diffuse" "blackbody L" 3000 "float scale" 8\n'
       'Shape "sphere" "float radius" 0.2\nAttributeEnd\n'
     + 'AttributeBegin\nMaterial "diffusetransmission" "rgb reflectance" [0.5 0.4 0.3] '
       '"rgb transmittance" [0.3 0.35 0.4] "float scale" 1.2\nRotate 80 1 0 0\n'
       'Shape "cylinder" "float radius" 0.7 "float zmin" -0.5 "float zmax" 0.5\nAttributeEnd\n'
     + 'Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]\n'
       'Shape "trianglemesh" "point3 P" [-4 -1 -4  4 -1 -4  4 -1 4  -4 -1 4] "integer indices" [0 1 2 0 2 3]\n'),
    # float and spectrum textures: a height image (bump.exr, written here) scaled into a
    # displacement, a colour PNG (amount.png: sRGB-decoded, channels averaged) mixing two
    # reflectances, on a quad with uv under a sky and a sun
    ("textures_bump_mix", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY + SUN
     + 'Texture "bump" "float" "imagemap" "string filename" "bump.exr"\n'
       'Texture "bumps" "float" "scale" "texture tex" "bump" "float scale" 0.08\n'
       'Texture "amt" "float" "imagemap" "string filename" "amount.png"\n'
       'Texture "colours" "spectrum" "mix" "rgb tex1" [0.8 0.2 0.1] "rgb tex2" [0.1 0.3 0.8] "texture amount" "amt"\n'
       'Material "diffuse" "texture reflectance" "colours" "texture displacement" "bumps"\n'
       'Shape "trianglemesh" "point3 P" [-1.5 -1.5 0  1.5 -1.5 0  1.5 1.5 0  -1.5 1.5 0] '
       '"point2 uv" [0 0 1 0 1 1 0 1] "integer indices" [0 1 2 0 2 3]\n'),
    # a mix material by an inverted float image, and a scaled spectrum image
    ("textures_mix_material", HEAD + 'Integrator "path" "integer maxdepth" 5\nWorldBegin\n' + SKY + SUN
     + 'Texture "inv" "float" "imagemap" "string filename" "amount.png" "bool invert" true\n'
       'Texture "img" "spectrum" "imagemap" "string filename" "amount.png" "float scale" 0.7\n'
       'MakeNamedMaterial "a" "string type" "diffuse" "texture reflectance" "img"\n'
       'MakeNamedMaterial "b" "string type" "conductor" "spectrum eta" "metal-Cu-eta" "spectrum k" "metal-Cu-k" "float roughness" 0.05\n'
       'Material "mix" "string materials" ["a" "b"] "texture amount" "inv"\n'
       'Shape "trianglemesh" "point3 P" [-1.5 -1.5 0  1.5 -1.5 0  1.5 1.5 0  -1.5 1.5 0] '
       '"point2 uv" [0 0 1 0 1 1 0 1] "integer indices" [0 1 2 0 2 3]\n'),
]


def write_texture_images(folder):
    """bump.exr: a smooth grey height field, one bump period across u and v (so that pbrt-v4's
    finite differences and spectrace's gradient agree); amount.png: an 8-bit colour image whose
    channels differ."""
    n = 128
    x = (np.arange(n) + 0.5) / n
    u, v = np.meshgrid(x, x)
    h = (0.5 + 0.25 * np.sin(2 * np.pi * u) * np.cos(2 * np.pi * v)).astype(np.float32)
    out = oiio.ImageOutput.create(os.path.join(folder, "bump.exr"))
    out.open(os.path.join(folder, "bump.exr"), oiio.ImageSpec(n, n, 1, "float"))
    out.write_image(h[..., None])
    out.close()
    m = 64
    y = (np.arange(m) + 0.5) / m
    a, b = np.meshgrid(y, y)
    rgb = np.stack([a, b, 0.5 + 0.4 * np.sin(6 * a)], -1)
    out = oiio.ImageOutput.create(os.path.join(folder, "amount.png"))
    out.open(os.path.join(folder, "amount.png"), oiio.ImageSpec(m, m, 3, "uint8"))
    out.write_image((rgb * 255 + 0.5).astype(np.uint8))
    out.close()


def square_to_sphere(u, v):
    """pbrt-v4's EqualAreaSquareToSphere (Clarberg's equal-area octahedral mapping)."""
    u, v = 2 * u - 1, 2 * v - 1
    up, vp = abs(u), abs(v)
    sd = 1 - (up + vp)
    r = 1 - abs(sd)
    phi = ((vp - up) / r + 1 if r != 0 else 1) * np.pi / 4
    z = np.copysign(1 - r * r, sd)
    s = r * np.sqrt(max(0.0, 2 - r * r))
    return np.copysign(np.cos(phi), u) * s, np.copysign(np.sin(phi), v) * s, z


def write_equal_area_map(path, n=32, glow=True):
    """A test map: a bluish sky brighter towards +z, a warm glow around (1, 1, 2) (unless
    `glow` is false), a dim ground."""
    img = np.zeros((n, n, 3), np.float32)
    sun = np.array([1.0, 1.0, 2.0]) / np.sqrt(6.0)
    for y in range(n):
        for x in range(n):
            d = np.array(square_to_sphere((x + 0.5) / n, (y + 0.5) / n))
            sky = np.array([0.3, 0.5, 0.9]) * (0.4 + 0.6 * max(d[2], 0.0))
            glow_v = np.array([3.0, 2.2, 1.2]) * max(float(d @ sun), 0.0) ** 8 if glow else 0.0
            ground = np.array([0.2, 0.15, 0.1]) if d[2] < 0 else 0.0
            img[y, x] = sky + glow_v + ground
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(n, n, 3, "float"))
    out.write_image(img)
    out.close()


def read_rgb(path):
    i = oiio.ImageInput.open(path)
    a = np.array(i.read_image(format="float"))
    i.close()
    return a[..., :3].astype(np.float64)


def main():
    out = ["# Written by scripts/gen_pbrt_refs.py with pbrt-v4 (../shared/tools/pbrt/build_pbrt.sh,",
           f"# mmp/pbrt-v4 5f7a6068): mean R, G, B, Y of 16 × 16 renders at {SPP} spp, seeds 1 and 2.", ""]
    eqarea = os.path.join(ROOT, "tests", "data", "pbrt", "eqarea.exr")
    write_equal_area_map(eqarea)
    # a white 16 × 16 map for tests/pbrt_import.rs's illuminance closed form
    white = os.path.join(ROOT, "tests", "data", "pbrt", "white.exr")
    out_img = oiio.ImageOutput.create(white)
    out_img.open(white, oiio.ImageSpec(16, 16, 3, "float"))
    out_img.write_image(np.ones((16, 16, 3), np.float32))
    out_img.close()
    write_texture_images(os.path.join(ROOT, "tests", "data", "pbrt"))
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copy(eqarea, tmp)
        for f in ("bump.exr", "amount.png"):
            shutil.copy(os.path.join(ROOT, "tests", "data", "pbrt", f), tmp)
        for name, text in CASES:
            scene = os.path.join(tmp, name + ".pbrt")
            with open(scene, "w") as f:
                f.write(text)
            imgs = []
            for seed in (1, 2):
                exr = os.path.join(tmp, f"{name}_{seed}.exr")
                subprocess.run([PBRT, "--quiet", "--seed", str(seed), "--outfile", exr, scene],
                               check=True, cwd=tmp)
                imgs.append(read_rgb(exr))
            ys = [0.2126 * a[..., 0] + 0.7152 * a[..., 1] + 0.0722 * a[..., 2] for a in imgs]
            n = ys[0].size
            se = float((ys[0] - ys[1]).std() / 2 / np.sqrt(n))
            rgb = ((imgs[0] + imgs[1]) / 2).reshape(-1, 3).mean(0)
            y = float((ys[0] + ys[1]).mean() / 2)
            # the object's pixels: those that differ from the background (the corners' value:
            # the sky, where a scene has one) by more than 2 %, so that an error in a shape or
            # a BSDF is not diluted by the background
            img = (ys[0] + ys[1]) / 2
            bg = float(np.median([img[0, 0], img[0, -1], img[-1, 0], img[-1, -1]]))
            mean = img.ravel()
            mask = np.nonzero(np.abs(mean - bg) > 0.02 * abs(bg) + 1e-9)[0]
            ym = float(mean[mask].mean()) if len(mask) else 0.0
            dm = (ys[0] - ys[1]).ravel()[mask]
            sem = float(dm.std() / 2 / np.sqrt(len(mask))) if len(mask) else 0.0
            print(name, rgb, y, se, len(mask), ym, sem)
            out += ["[[case]]", f'name = "{name}"', f"spp = {SPP}", f"pbrt = '''\n{text}'''",
                    "rgb = [" + ", ".join(f"{v:.7g}" for v in rgb) + "]",
                    f"y = {y:.7g}", f"stderr = {se:.4g}",
                    "object = [" + ", ".join(str(int(i)) for i in mask) + "]",
                    f"y_object = {ym:.7g}", f"stderr_object = {sem:.4g}", ""]
    with open(os.path.join(ROOT, "tests", "data", "pbrt_refs.toml"), "w") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main()
