#!/usr/bin/env python3
"""Writes tests/data/mitsuba_plugin_refs.toml: numbers Mitsuba 3.9.1 itself renders for the
plugins and parameters of issue 31, which tests/mitsuba_data_plugins.rs holds spectrace to.

Each [[case]] is a small scene (16 × 16 pixels, box filter, XYZ film, `scalar_spectral`) and
the mean X, Y, Z over the image of two renders with seeds 0 and 1, with the standard error of
that mean (the standard deviation of the per-pixel difference of the seeds / 2 / √pixels).

Usage: pip install mitsuba==3.9.1 (and apt-get install libllvm19 for the sdfgrid cases, which
Mitsuba traces with its LLVM variant); python3 scripts/gen_mitsuba_plugin_refs.py
"""
import os

import numpy as np

# the LLVM variant (for sdfgrid) needs libLLVM: apt-get install libllvm19
os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1")
import mitsuba as mi  # noqa: E402

mi.set_variant("scalar_spectral")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPP = int(os.environ.get("SPP", "64"))


def sensor(origin="0, 0, 3", target="0, 0, 0", up="0, 1, 0", fov=10):
    return f"""<sensor type="perspective"><float name="fov" value="{fov}"/>
<transform name="to_world"><lookat origin="{origin}" target="{target}" up="{up}"/></transform>
<sampler type="independent"><integer name="sample_count" value="{SPP}"/></sampler>
<film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
<string name="pixel_format" value="xyz"/><rfilter type="box"/></film></sensor>"""


def projector(irradiance):
    """A projector 2 m above a white diffuse plane, seen from 3 m: its irradiance given as a
    number or RGB (an emission: D65-shaped in spectral variants, of any magnitude)."""
    return f"""<integrator type="direct"/>{sensor()}
<shape type="rectangle"><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></shape>
<emitter type="projector"><float name="fov" value="40"/>
<transform name="to_world"><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform>
{irradiance}</emitter>"""


def write_bmp(path, rgb):
    """A 24-bit uncompressed BMP (BITMAPINFOHEADER, rows bottom-up, BGR, rows padded to 4
    bytes), written from the format's definition."""
    h, w, _ = rgb.shape
    row = (3 * w + 3) // 4 * 4
    pixels = bytearray()
    for y in range(h - 1, -1, -1):
        line = bytearray()
        for x in range(w):
            r, g, b = (int(v) for v in rgb[y, x])
            line += bytes([b, g, r])
        pixels += line + bytes(row - len(line))
    header = b"BM" + (54 + len(pixels)).to_bytes(4, "little") + bytes(4) + (54).to_bytes(4, "little")
    info = ((40).to_bytes(4, "little") + w.to_bytes(4, "little", signed=True)
            + h.to_bytes(4, "little", signed=True) + (1).to_bytes(2, "little")
            + (24).to_bytes(2, "little") + bytes(4) + len(pixels).to_bytes(4, "little")
            + (2835).to_bytes(4, "little") * 2 + bytes(8))
    with open(path, "wb") as f:
        f.write(header + info + pixels)


def image_files():
    """tests/data/mitsuba_plugins/: an 8 × 4 colour BMP (an emitter's radiance) and an 8 × 8
    colour PNG of ridges (a bump map read raw: its luminance is the height)."""
    folder = os.path.join(ROOT, "tests", "data", "mitsuba_plugins")
    os.makedirs(folder, exist_ok=True)
    y, x = np.mgrid[0:4, 0:8]
    bmp = np.stack([30 * x + 20, 60 * y + 10, 255 - 25 * x], axis=-1).astype(np.uint8)
    write_bmp(os.path.join(folder, "panel.bmp"), bmp)
    y, x = np.mgrid[0:8, 0:8]
    ridge = 0.5 + 0.5 * np.sin(2 * np.pi * x / 8)
    png = np.stack([ridge * 200, ridge * 120 + 60 * (y / 7), 255 - ridge * 100], axis=-1)
    mi.Bitmap(png.astype(np.uint8), pixel_format=mi.Bitmap.PixelFormat.RGB).write(
        os.path.join(folder, "ridges.png"))
    # a 2 × 2 grid of quads (9 vertices, 8 triangles: Mitsuba reads triangles only) with vertex colours,
    # face colours (bare red/green/blue, floats) and a one-field face weight
    lines = ["ply", "format ascii 1.0", "element vertex 9", "property float x", "property float y",
             "property float z", "property float color_0", "property float color_1",
             "property float color_2", "element face 8", "property list uchar int vertex_indices",
             "property float red", "property float green", "property float blue",
             "property float weight_0", "end_header"]
    for j in range(3):
        for i in range(3):
            lines.append(f"{i - 1} {j - 1} 0 {0.1 + 0.4 * i} {0.8 - 0.3 * j} {0.2 + 0.2 * i * j}")
    faces = [(0, 1, 4, 3), (1, 2, 5, 4), (3, 4, 7, 6), (4, 5, 8, 7)]
    colours = [(0.9, 0.2, 0.1), (0.1, 0.7, 0.3), (0.2, 0.3, 0.9), (0.8, 0.8, 0.2)]
    for k, (f, c) in enumerate(zip(faces, colours)):
        for tri in ((f[0], f[1], f[2]), (f[0], f[2], f[3])):
            lines.append(f"3 {tri[0]} {tri[1]} {tri[2]} {c[0]} {c[1]} {c[2]} {0.2 + 0.2 * k}")
    with open(os.path.join(folder, "grid_attributes.ply"), "w") as f:
        f.write("\n".join(lines) + "\n")
    # a 20 × 20 × 20 .vol grid (version 3, float32, one channel, x fastest) of the distance to
    # a torus of radii 0.28 and 0.12 around the cube's centre, tilted: an sdfgrid
    n = 20
    z, y, x = np.mgrid[0:n, 0:n, 0:n] / (n - 1) - 0.5
    y, z = 0.8 * y - 0.6 * z, 0.6 * y + 0.8 * z
    sdf = np.sqrt((np.sqrt(x * x + y * y) - 0.28) ** 2 + z * z) - 0.12
    header = b"VOL" + bytes([3]) + np.array([1, n, n, n, 1], "<i4").tobytes() \
        + np.array([0, 0, 0, 1, 1, 1], "<f4").tobytes()
    with open(os.path.join(folder, "torus.vol"), "wb") as f:
        f.write(header + sdf.astype("<f4").tobytes())


# `{data}` stands for tests/data/mitsuba_plugins (the test substitutes its own path)
LIT = """<emitter type="directional"><vector name="direction" value="-0.6, -0.3, -1"/>
<rgb name="irradiance" value="2"/></emitter>"""

CASES = [
    ("projector_rgb_1", projector('<rgb name="irradiance" value="1"/>')),
    ("projector_float_1", projector('<float name="irradiance" value="1"/>')),
    ("projector_rgb_bright", projector('<rgb name="irradiance" value="25.5 38.0 20.1"/>')),
    ("projector_rgb_scaled",
     projector('<rgb name="irradiance" value="0.255 0.38 0.201"/><float name="scale" value="3"/>')),
    # Mitsuba's particle tracer: a point light over a diffuse plane, and an area light seen
    # directly (the emitter's own vertex connected to the sensor)
    ("ptracer_point", f"""<integrator type="ptracer"><integer name="max_depth" value="3"/></integrator>
{sensor(fov=30)}<shape type="rectangle"><bsdf type="diffuse"/></shape>
<emitter type="point"><point name="position" value="0.3, 0.2, 1"/><rgb name="intensity" value="2"/></emitter>"""),
    ("ptracer_area", f"""<integrator type="ptracer"/>{sensor(fov=30)}
<shape type="rectangle"><bsdf type="diffuse"/></shape>
<shape type="disk"><transform name="to_world"><scale value="0.1"/><rotate x="1" angle="180"/>
<translate value="0.1, 0, 0.5"/></transform><emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>
<shape type="disk"><transform name="to_world"><scale value="0.15"/><translate value="-0.2, 0.1, 0.3"/></transform>
<emitter type="area"><rgb name="radiance" value="0.5 0.8 0.2"/></emitter></shape>"""),
    # a normalmap of a rawconstant normal: (0.5, 0.5, 1) is the unperturbed normal, (0.75,
    # 0.5, 0.9) a tilted one, on a plane under a slanted directional light
    ("normalmap_raw_identity", f"""<integrator type="path"><integer name="max_depth" value="2"/></integrator>
{sensor(fov=30)}{LIT}<shape type="rectangle"><bsdf type="normalmap">
<texture name="normalmap" type="rawconstant"><vector name="value" value="0.5, 0.5, 1"/></texture>
<bsdf type="roughconductor"><string name="material" value="Al"/><float name="alpha" value="0.3"/></bsdf>
</bsdf></shape>"""),
    ("normalmap_raw_tilted", f"""<integrator type="path"><integer name="max_depth" value="2"/></integrator>
{sensor(fov=30)}{LIT}<shape type="rectangle"><bsdf type="normalmap">
<texture name="normalmap" type="rawconstant"><vector name="value" value="0.75, 0.5, 0.9"/></texture>
<bsdf type="diffuse"/></bsdf></shape>"""),
    # a colour PNG read raw as a bump map: Mitsuba's eval_1 takes its luminance
    ("bumpmap_colour_raw", f"""<integrator type="path"><integer name="max_depth" value="2"/></integrator>
{sensor(fov=30)}{LIT}<shape type="rectangle"><bsdf type="bumpmap"><float name="scale" value="0.3"/>
<texture type="bitmap"><string name="filename" value="{{data}}/ridges.png"/><boolean name="raw" value="true"/></texture>
<bsdf type="diffuse"/></bsdf></shape>"""),
    # mesh attributes on a flat-lit plane: vertex colours blended as spectra, face colours,
    # a face weight blending two diffuse BSDFs, and a scaled vertex colour
    *[(f"mesh_attribute_{tag}", f"""<integrator type="direct"/>{sensor(fov=45)}{LIT}
<shape type="ply"><string name="filename" value="{{data}}/grid_attributes.ply"/>{bsdf}</shape>""")
      for tag, bsdf in [
          ("vertex_color", '<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance">'
                           '<string name="name" value="vertex_color"/></texture></bsdf>'),
          ("face_color", '<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance">'
                         '<string name="name" value="face_color"/></texture></bsdf>'),
          ("face_weight", '<bsdf type="blendbsdf"><texture type="mesh_attribute" name="weight">'
                          '<string name="name" value="face_weight"/></texture>'
                          '<bsdf type="diffuse"><rgb name="reflectance" value="0 0.5 0.5"/></bsdf>'
                          '<bsdf type="diffuse"><rgb name="reflectance" value="1 1 0"/></bsdf></bsdf>'),
          ("scaled", '<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance">'
                     '<string name="name" value="vertex_color"/><float name="scale" value="0.5"/>'
                     '</texture></bsdf>'),
      ]],
    # a sphere's uv follows its to_world rotation (φ from the object's +x, θ from its +z):
    # coarse checks on a rotated sphere under a slanted light
    ("sphere_uv_rotated", f"""<integrator type="direct"/>{sensor(fov=45)}{LIT}
<shape type="sphere"><transform name="to_world"><rotate z="1" angle="225"/><rotate x="1" angle="30"/>
<translate z="0.2"/></transform><bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
<rgb name="color0" value="0.9"/><rgb name="color1" value="0.1"/>
<transform name="to_uv"><scale x="2" y="2"/></transform></texture></bsdf></shape>"""),
    # Mitsuba's microfacet G is G1(wo)·G1(wi): very rough GGX and Beckmann metal and glass under
    # a grazing light, where it differs most from the height-correlated G
    *[(f"smith_{tag}", f"""<integrator type="path"><integer name="max_depth" value="3"/></integrator>
{sensor(fov=45)}<emitter type="directional"><vector name="direction" value="-1, 0, -0.15"/>
<rgb name="irradiance" value="3"/></emitter><shape type="sphere"><transform name="to_world"><translate z="0.3"/></transform>{bsdf}</shape>
<shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><bsdf type="diffuse"/></shape>""")
      for tag, bsdf in [
          ("conductor_ggx", '<bsdf type="roughconductor"><string name="distribution" value="ggx"/>'
                            '<float name="alpha" value="0.7"/></bsdf>'),
          ("conductor_beckmann", '<bsdf type="roughconductor"><string name="material" value="Au"/>'
                                 '<float name="alpha" value="0.6"/></bsdf>'),
          ("dielectric_ggx", '<bsdf type="roughdielectric"><string name="distribution" value="ggx"/>'
                             '<float name="alpha" value="0.6"/></bsdf>'),
      ]],
    # a checkerboard read as one number (roughness, opacity, blend weight): Mitsuba's eval_1
    # gives color0 where its spectral eval gives color1
    *[(f"checker_scalar_{tag}", f"""<integrator type="path"><integer name="max_depth" value="8"/></integrator>
{sensor(fov=45)}{LIT}<shape type="rectangle"><transform name="to_world"><scale value="1.2"/></transform>
<bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
<shape type="sphere"><transform name="to_world"><translate z="0.4"/></transform>{bsdf}</shape>""")
      for tag, bsdf in [
          ("alpha", '<bsdf type="roughconductor"><texture type="checkerboard" name="alpha">'
                    '<float name="color0" value="0.05"/><float name="color1" value="0.6"/>'
                    '<transform name="to_uv"><scale x="2" y="1"/></transform></texture></bsdf>'),
          ("opacity", '<bsdf type="mask"><texture type="checkerboard" name="opacity">'
                      '<float name="color0" value="0.1"/><float name="color1" value="0.9"/>'
                      '<transform name="to_uv"><scale x="2" y="1"/></transform></texture>'
                      '<bsdf type="diffuse"><rgb name="reflectance" value="0.8 0.2 0.1"/></bsdf></bsdf>'),
          ("weight", '<bsdf type="blendbsdf"><texture type="checkerboard" name="weight">'
                     '<float name="color0" value="0"/><float name="color1" value="1"/>'
                     '<transform name="to_uv"><scale x="2" y="1"/></transform></texture>'
                     '<bsdf type="diffuse"><rgb name="reflectance" value="0.9 0.1 0.1"/></bsdf>'
                     '<bsdf type="diffuse"><rgb name="reflectance" value="0.1 0.1 0.9"/></bsdf></bsdf>'),
      ]],
    # linear curves (tests/data/mitsuba_plugins/zigzag.txt, written by hand): a zig-zag of
    # capsules with spherical joints and a second, thinner curve, scaled (radii are not)
    ("linearcurve_zigzag", f"""<integrator type="path"><integer name="max_depth" value="3"/></integrator>
{sensor(fov=45)}{LIT}<shape type="rectangle"><transform name="to_world"><scale value="3"/>
<translate z="-1.2"/></transform><bsdf type="diffuse"/></shape>
<shape type="linearcurve"><string name="filename" value="{{data}}/zigzag.txt"/>
<transform name="to_world"><rotate x="1" angle="70"/><scale x="1.2"/></transform>
<bsdf type="diffuse"><rgb name="reflectance" value="0.8 0.3 0.1"/></bsdf></shape>"""),
    # B-spline curves (tests/data/mitsuba_plugins/wave.txt, written by hand): one of varying
    # radius and a thinner one, scaled (radii are not), open at their ends
    ("bsplinecurve_wave", f"""<integrator type="path"><integer name="max_depth" value="3"/></integrator>
{sensor(fov=45)}{LIT}<shape type="rectangle"><transform name="to_world"><scale value="3"/>
<translate z="-1.2"/></transform><bsdf type="diffuse"/></shape>
<shape type="bsplinecurve"><string name="filename" value="{{data}}/wave.txt"/>
<transform name="to_world"><rotate x="1" angle="60"/><rotate z="1" angle="20"/><scale x="1.2"/></transform>
<bsdf type="diffuse"><texture type="checkerboard" name="reflectance"><rgb name="color0" value="0.8 0.3 0.1"/>
<rgb name="color1" value="0.1 0.4 0.8"/><transform name="to_uv"><scale x="4" y="6"/></transform></texture></bsdf></shape>"""),
    # an sdfgrid (torus.vol) in a shapegroup placed by an instance, with smooth and analytic
    # normals, on a floor
    *[(f"sdfgrid_{normals}", f"""<integrator type="path"><integer name="max_depth" value="3"/></integrator>
{sensor(fov=45)}{LIT}<shape type="rectangle"><transform name="to_world"><scale value="3"/>
<translate z="-0.6"/></transform><bsdf type="diffuse"/></shape>
<shape type="shapegroup" id="g"><shape type="sdfgrid"><string name="filename" value="{{data}}/torus.vol"/>
<string name="normals" value="{normals}"/><bsdf type="diffuse"><rgb name="reflectance" value="0.2 0.3 0.8"/></bsdf>
</shape></shape><shape type="instance"><ref id="g"/><transform name="to_world"><translate value="-0.5, -0.5, -0.5"/>
<scale value="1.6"/><rotate z="1" angle="30"/></transform></shape>""")
      for normals in ["smooth", "analytic"]],
    # a cylinder stretched along its axis (test_various_shapes scales one so)
    ("cylinder_stretched", f"""<integrator type="direct"/>{sensor(fov=45)}{LIT}
<shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-0.5"/></transform>
<bsdf type="diffuse"/></shape><shape type="cylinder"><float name="radius" value="0.2"/>
<transform name="to_world"><scale x="1.5" y="1.5" z="0.6"/><rotate x="1" angle="-35"/></transform>
<bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.7 0.5 0.2"/></bsdf></bsdf></shape>"""),
    # the principled BSDFs: every lobe on a sphere (anisotropic along the sphere's ∂p/∂u), the
    # tints (Mitsuba's spectral luminance of the base colour), rough glass, and the thin sheet
    # lit from both sides
    *[(f"principled_{tag}", f"""<integrator type="path"><integer name="max_depth" value="6"/></integrator>
{sensor(fov=40)}{LIT}<emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>
<shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-0.5"/></transform>
<bsdf type="diffuse"/></shape><shape type="sphere"><float name="radius" value="0.45"/>{bsdf}</shape>""")
      for tag, bsdf in [
          ("lobes", '<bsdf type="principled"><rgb name="base_color" value="0.8 0.3 0.1"/>'
                    '<float name="roughness" value="0.35"/><float name="metallic" value="0.4"/>'
                    '<float name="anisotropic" value="0.6"/><float name="sheen" value="0.8"/>'
                    '<float name="clearcoat" value="0.7"/><float name="clearcoat_gloss" value="0.5"/>'
                    '<float name="flatness" value="0.4"/><float name="specular" value="0.6"/></bsdf>'),
          ("tints", '<bsdf type="principled"><rgb name="base_color" value="0.2 0.7 0.3"/>'
                    '<float name="roughness" value="0.3"/><float name="spec_tint" value="0.8"/>'
                    '<float name="sheen" value="1"/><float name="sheen_tint" value="0.9"/></bsdf>'),
          ("glass", '<bsdf type="principled"><rgb name="base_color" value="0.9 0.8 0.6"/>'
                    '<float name="roughness" value="0.3"/><float name="spec_trans" value="0.9"/>'
                    '<float name="eta" value="1.5"/></bsdf>'),
          ("thin", '<bsdf type="principledthin"><rgb name="base_color" value="0.3 0.6 0.9"/>'
                   '<float name="roughness" value="0.4"/><float name="spec_trans" value="0.4"/>'
                   '<float name="diff_trans" value="0.9"/><float name="sheen" value="0.5"/>'
                   '<float name="eta" value="1.4"/></bsdf>'),
      ]],
    # Chiang's hair under a slanted light and a constant sky, on a patch of twelve parallel
    # fibres that fills the view (tests/data/mitsuba_plugins/hair_patch.txt, written by a
    # loop: 7 points each along +y, radius 0.09, spaced 0.2): the default brown on B-splines;
    # light pigments with a steep scale tilt (which tells the fibres' direction apart); a σₐ
    # spectrum
    *[(f"hair_{tag}", f"""<integrator type="path"><integer name="max_depth" value="12"/></integrator>
{sensor(fov=30)}{LIT}<emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>
<shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-0.6"/></transform>
<bsdf type="diffuse"/></shape><shape type="{curve}"><string name="filename" value="{{data}}/{file}"/>
<transform name="to_world"><rotate z="1" angle="20"/></transform>
{bsdf}</shape>""")
      for tag, curve, file, bsdf in [
          ("brown", "bsplinecurve", "hair_patch.txt", '<bsdf type="hair"/>'),
          ("light_tilted", "bsplinecurve", "hair_patch.txt",
           '<bsdf type="hair"><float name="eumelanin" value="0.1"/><float name="pheomelanin" value="0.3"/>'
           '<float name="scale_tilt" value="8"/><float name="longitudinal_roughness" value="0.2"/>'
           '<float name="azimuthal_roughness" value="0.4"/></bsdf>'),
          # (on B-splines: Mitsuba 3.9.1 gives a linearcurve no ∂p/∂u, so that its hair
          # sees an arbitrary frame there; see the README)
          ("sigma", "bsplinecurve", "hair_patch.txt",
           '<bsdf type="hair"><spectrum name="sigma_a" value="400:0.1, 500:0.3, 600:0.6, 700:1.2"/>'
           '<float name="scale" value="0.8"/><float name="int_ior" value="1.5"/></bsdf>'),
      ]],
    # a BMP as an emitter's radiance (sRGB 8-bit values, as a PNG's)
    ("bmp_radiance", f"""<integrator type="path"><integer name="max_depth" value="1"/></integrator>
{sensor(fov=30)}<shape type="rectangle"><emitter type="area"><texture name="radiance" type="bitmap">
<string name="filename" value="{{data}}/panel.bmp"/><string name="filter_type" value="nearest"/></texture></emitter></shape>"""),
]


def render(body, seed):
    # Mitsuba's scalar variants trace an sdfgrid only with Embree; its LLVM variant always
    variant = "llvm_ad_spectral" if "sdfgrid" in body else "scalar_spectral"
    mi.set_variant(variant)
    data = os.path.join(ROOT, "tests", "data", "mitsuba_plugins")
    scene = mi.load_string(f'<scene version="3.0.0">{body.replace("{data}", data)}</scene>')
    return np.array(mi.render(scene, seed=seed), dtype=np.float64)[:, :, :3]


def main():
    out = ["# Written by scripts/gen_mitsuba_plugin_refs.py with Mitsuba 3.9.1 scalar_spectral:",
           f"# mean X, Y, Z of 16 × 16 renders at {SPP} spp, two seeds, and their standard errors.", ""]
    image_files()
    for name, body in CASES:
        a, b = render(body, 0), render(body, 1)
        mean = (a + b).reshape(-1, 3).mean(0) / 2
        se = (a - b).reshape(-1, 3).std(0) / 2 / np.sqrt(a.shape[0] * a.shape[1])
        out += ["[[case]]", f'name = "{name}"', f"spp = {SPP}",
                "xml = '''" + body + "'''",
                "xyz = [" + ", ".join(f"{v:.7g}" for v in mean) + "]",
                "stderr = [" + ", ".join(f"{v:.3g}" for v in se) + "]", ""]
        print(name, mean, se)
    with open(os.path.join(ROOT, "tests", "data", "mitsuba_plugin_refs.toml"), "w") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main()
