//! pbrt-v4's lights (`src/pbrt/lights.cpp`): `LightSource` kinds, with pbrt-v4's photometric
//! normalisations (the `AreaLightSource` state is in `area_light.rs`).

use std::f64::consts::PI;

use glam::{DMat4, DVec3};

use super::params::{Params, R};
use super::shapes::len;
use super::{Reader, spectra};
use crate::loader::Loc;
use crate::loader::desc::*;
use crate::spectrum::Spectrum;
use crate::texture::{TexFilter, Wrap};
use crate::units::{Angle, angle::degree};

/// The CTM's x, y and z axes made unit, as directions: a light's frame, on which a uniform
/// scale has no effect in pbrt-v4 (it looks directions up normalised).
fn unit_axes(ctm: &DMat4) -> [glam::DVec4; 3] {
    [0, 1, 2].map(|i| ctm.col(i).truncate().normalize_or_zero().extend(0.0))
}

/// A light's image as a texture: clamped at its edges, 8- and 16-bit files decoded from sRGB
/// (pbrt-v4's `Image::Read`), colours unbounded (each texel's `RGBIlluminantSpectrum` before its
/// illuminant), looked up with `filter` after `to_uv`.
pub(super) fn light_texture(
    path: std::path::PathBuf,
    filter: TexFilter,
    to_uv: Vec<crate::loader::desc::TransformStep>,
    loc: Loc,
) -> TextureDesc {
    TextureDesc::PbrtImage(Box::new(PbrtImageDesc {
        path,
        filter,
        wrap: Wrap::Clamp,
        to_uv,
        srgb: true,
        grey: false,
        scale: 1.0,
        invert: false,
        unbounded: true,
        loc,
    }))
}

/// The linear RGB pixels of a light's image and its width (8- and 16-bit files decoded from
/// sRGB, as pbrt-v4's `Image::Read` reads them), or an error at `filename`.
pub(super) fn light_image(p: &Params, path: &std::path::Path) -> R<(Vec<[f64; 3]>, usize)> {
    let img =
        crate::image_io::read_rgb(path).map_err(|e| p.err(p.loc_of("filename"), e.to_string()))?;
    let decode = img.encoding == crate::image_io::Encoding::Srgb;
    let lin = |v: f32| {
        if decode {
            crate::colour::spaces::srgb_decode(v as f64)
        } else {
            v as f64
        }
    };
    Ok((img.rgb.iter().map(|px| px.map(lin)).collect(), img.width))
}

/// Luminance of a linear sRGB colour (the colour space's Y row, as pbrt-v4's
/// `LuminanceVector`).
pub(super) fn luminance(c: [f64; 3]) -> f64 {
    0.212_639 * c[0] + 0.715_169 * c[1] + 0.072_192 * c[2]
}

/// A `LightSource`.
pub(super) fn light(kind: &str, p: &Params, ctm: &DMat4, loc: Loc, r: &Reader) -> R<LightDesc> {
    let scale = p.float("scale", 1.0)?;
    let (kind, spectrum) = match kind {
        "point" => {
            let from = ctm.transform_point3(DVec3::from(p.vec3("from", [0.0; 3])?));
            let (s, k) = spectra::illuminant(p, "I")?;
            // pbrt-v4's `power` sets ∫ȳ·Φ dλ (its luminous units) over 4π sr
            let power = p.float("power", -1.0)?;
            let k = if power > 0.0 {
                k * power / (4.0 * PI)
            } else {
                k
            };
            (
                LightKind::Point {
                    position: [len(from.x), len(from.y), len(from.z)],
                    amount: PointAmount::Scale(scale * k),
                },
                s,
            )
        }
        // pbrt-v4's spot: full inside coneangle − conedeltaangle, smoothstep in cos θ to 0 at
        // coneangle (`SpotLight::I`); `power` over the cone as pbrt-v4 integrates it
        "spot" => {
            let from = DVec3::from(p.vec3("from", [0.0; 3])?);
            let to = DVec3::from(p.vec3("to", [0.0, 0.0, 1.0])?);
            if (to - from).length() == 0.0 {
                return Err(p.err(loc, "a spot light's from and to coincide"));
            }
            let cone = p.float("coneangle", 30.0)?;
            let delta = p.float("conedeltaangle", 5.0)?;
            if !(cone > 0.0 && cone <= 180.0 && (0.0..=cone).contains(&delta)) {
                return Err(p.err(
                    loc,
                    "a spot light needs 0 < coneangle ≤ 180 and 0 ≤ conedeltaangle ≤ coneangle (degrees)",
                ));
            }
            let (s, k) = spectra::illuminant(p, "I")?;
            let power = p.float("power", -1.0)?;
            let (cos_end, cos_start) = (cone.to_radians().cos(), (cone - delta).to_radians().cos());
            let k = if power > 0.0 {
                k * power / (2.0 * PI * ((1.0 - cos_start) + (cos_start - cos_end) / 2.0))
            } else {
                k
            };
            let (from, to) = (ctm.transform_point3(from), ctm.transform_point3(to));
            (
                LightKind::Spot {
                    position: [len(from.x), len(from.y), len(from.z)],
                    target: [len(to.x), len(to.y), len(to.z)],
                    cone_angle: Angle::new::<degree>(cone),
                    falloff_start: Angle::new::<degree>(cone - delta),
                    falloff: crate::light::SpotFalloff::SmoothstepCos,
                    amount: PointAmount::Scale(scale * k),
                    texture: None,
                },
                s,
            )
        }
        "distant" => {
            let from = DVec3::from(p.vec3("from", [0.0, 0.0, 0.0])?);
            let to = DVec3::from(p.vec3("to", [0.0, 0.0, 1.0])?);
            let dir = ctm.transform_vector3(to - from);
            let Some(dir) = dir.try_normalize() else {
                return Err(p.err(loc, "a distant light's from and to coincide"));
            };
            let (s, k) = spectra::illuminant(p, "L")?;
            // `illuminance`: ∫ȳ·E dλ on a plane facing the light
            let e = p.float("illuminance", -1.0)?;
            let k = if e > 0.0 { k * e } else { k };
            (
                LightKind::Directional {
                    direction: dir.to_array(),
                    angular_diameter: Angle::new::<degree>(0.0),
                    amount: DirectionalAmount::Scale(scale * k),
                },
                s,
            )
        }
        "projection" => return projection(p, ctm, loc, r, scale),
        "goniometric" => return goniometric(p, ctm, loc, r, scale),
        "infinite" if p.get("filename").is_some() => {
            return image_infinite(p, ctm, loc, r, scale);
        }
        "infinite" => {
            let (s, k) = spectra::illuminant(p, "L")?;
            // `illuminance`: ∫ȳ·E dλ on an upward plane, π·L for a uniform sky
            let e = p.float("illuminance", -1.0)?;
            let k = if e > 0.0 { k * e / PI } else { k };
            (
                LightKind::Environment {
                    amount: EmitAmount::Scale(scale * k),
                },
                s,
            )
        }
        other => {
            return Err(p.err(
                loc,
                format!("the light \"{other}\" is not read yet (spectrace reads point, spot, goniometric, projection, distant and infinite)"),
            ));
        }
    };
    Ok(LightDesc {
        kind,
        spectrum,
        sampling_weight: 1.0,
        loc,
    })
}

/// An image `infinite` light: a square image in pbrt-v4's equal-area octahedral layout under
/// the CTM, each pixel's RGB an `RGBIlluminantSpectrum` of the sRGB space (its D65 of luminance
/// 1), times `scale`; `illuminance` (∫ȳ·E dλ on a plane facing the map's +z) sets the map's
/// illuminance to `scale` times it. pbrt-v4 measures the map's own illuminance with half each
/// pixel's solid angle (2π/N² for 4π/N²), so its renders of such a map are twice as bright as
/// asked (README); spectrace gives the illuminance asked for.
fn image_infinite(p: &Params, ctm: &DMat4, loc: Loc, r: &Reader, scale: f64) -> R<LightDesc> {
    if let Some(q) = p.get("L") {
        return Err(p.err(
            q.loc,
            "an infinite light takes \"L\" or \"filename\", not both (pbrt-v4)",
        ));
    }
    if let Some(q) = p.get("portal") {
        return Err(p.err(q.loc, "an infinite light's \"portal\" is not read yet"));
    }
    let name = p.string("filename")?.unwrap_or_default();
    let path = r.resolve(&r.root, &name);
    if !path.is_file() {
        return Err(p.err(
            p.loc_of("filename"),
            format!("no image \"{}\"", path.display()),
        ));
    }
    let e = p.float("illuminance", -1.0)?;
    let amount = if e > 0.0 {
        let lux = crate::colour::cie::K_M * scale * e;
        EnvMapAmount::Illuminance(crate::units::Illuminance::new::<
            crate::units::illuminance::lux,
        >(lux))
    } else {
        EnvMapAmount::Scale(scale)
    };
    Ok(LightDesc {
        kind: LightKind::OctahedralMap {
            path,
            transform: vec![super::placed::matrix_step(ctm)],
            amount,
        },
        spectrum: Spectrum::Piecewise(crate::spectrum::rgb2spec::d65_unit_luminance()),
        sampling_weight: 1.0,
        loc,
    })
}

/// A `projection` light (pbrt-v4's `ProjectionLight`): the image `filename` thrown from the
/// CTM's origin along its +z, `fov` (degrees, 90 by default) across the image's shorter axis;
/// each pixel's RGB (8- and 16-bit files decoded from sRGB, as pbrt-v4's `Image::Read`) an
/// `RGBIlluminantSpectrum` of the sRGB space (its D65 of luminance 1) times `scale`, looked up at the nearest pixel, as an intensity constant over the pixel's
/// directions (no cos³ law: [`crate::light::ProjectorLaw::Intensity`]). `power` (∫ȳ·Φ dλ
/// over the frustum) sets the scale as pbrt-v4 does: power / (A · the mean over pixels of
/// lum(rgb)·cos³θ at their centres), A the image's area on the plane z = 1.
fn projection(p: &Params, ctm: &DMat4, loc: Loc, r: &Reader, scale: f64) -> R<LightDesc> {
    let name = p
        .string("filename")?
        .ok_or_else(|| p.err(loc, "a projection light needs a \"string filename\""))?;
    let path = r.resolve(&r.root, &name);
    if !path.is_file() {
        return Err(p.err(
            p.loc_of("filename"),
            format!("no image \"{}\"", path.display()),
        ));
    }
    let fov = p.float("fov", 90.0)?;
    if !(fov > 0.0 && fov < 180.0) {
        return Err(p.err(
            p.loc_of("fov"),
            format!("fov must lie in (0, 180) degrees, not {fov}"),
        ));
    }
    let power = p.float("power", -1.0)?;
    let k = if power > 0.0 {
        let (rgb, w) = light_image(p, &path)?;
        let h = rgb.len() / w;
        let aspect = w as f64 / h as f64;
        let (ax, ay) = if aspect > 1.0 {
            (aspect, 1.0)
        } else {
            (1.0, 1.0 / aspect)
        };
        let t = (fov.to_radians() / 2.0).tan();
        let mut sum = 0.0;
        for (i, px) in rgb.iter().enumerate() {
            let sx = ax * (2.0 * ((i % w) as f64 + 0.5) / w as f64 - 1.0);
            let sy = ay * (2.0 * ((i / w) as f64 + 0.5) / h as f64 - 1.0);
            let cos3 = (1.0 + t * t * (sx * sx + sy * sy)).powf(-1.5);
            sum += luminance(*px) * cos3;
        }
        let area = 4.0 * t * t * ax * ay;
        let mean = sum / (w * h) as f64;
        if !(mean > 0.0) {
            return Err(p.err(
                p.loc_of("power"),
                "a projection light with \"power\" needs an image that is not black",
            ));
        }
        power / (area * mean)
    } else {
        1.0
    };
    // spectrace's projector has u growing toward its local −x (pbrt-v4's toward +x, after its
    // y flip has v growing toward −y as here): its frame is the light's (−x, y, z)
    let [x, y, z] = unit_axes(ctm);
    let frame = DMat4::from_cols(-x, y, z, ctm.col(3));
    let image = light_texture(path, TexFilter::Nearest, Vec::new(), loc);
    let d65 = Spectrum::Piecewise(crate::spectrum::rgb2spec::d65_unit_luminance());
    Ok(LightDesc {
        kind: LightKind::Projector {
            transform: vec![super::placed::matrix_step(&frame)],
            fov: Angle::new::<degree>(fov),
            fov_axis: FovAxis::Smaller,
            image,
            constant_intensity: true,
        },
        spectrum: d65.scaled((scale * k) as f32),
        sampling_weight: 1.0,
        loc,
    })
}

/// A `goniometric` light (pbrt-v4's `GoniometricLight`): at the CTM's origin, its intensity
/// `I` (a spectrum of luminance 1, times `scale`) times the grey of the square image
/// `filename` (the mean of its linear R, G, B), laid over the sphere in the equal-area
/// octahedral layout after pbrt-v4's swap of the light's y and z axes (the image's centre
/// along the light's +y). `power` (∫ȳ·Φ dλ) sets the scale to power / (4π · mean pixel), as
/// pbrt-v4 does. Without `filename` pbrt-v4 warns and emits nothing; here it is an error.
fn goniometric(p: &Params, ctm: &DMat4, loc: Loc, r: &Reader, scale: f64) -> R<LightDesc> {
    let name = p.string("filename")?.ok_or_else(|| {
        p.err(
            loc,
            "a goniometric light needs a \"string filename\" (pbrt-v4 warns and emits nothing)",
        )
    })?;
    let path = r.resolve(&r.root, &name);
    if !path.is_file() {
        return Err(p.err(
            p.loc_of("filename"),
            format!("no image \"{}\"", path.display()),
        ));
    }
    let (s, k) = spectra::illuminant(p, "I")?;
    let power = p.float("power", -1.0)?;
    let k = if power > 0.0 {
        let (rgb, _) = light_image(p, &path)?;
        let sum: f64 = rgb.iter().map(|px| (px[0] + px[1] + px[2]) / 3.0).sum();
        let mean = sum / rgb.len().max(1) as f64;
        if !(mean > 0.0) {
            return Err(p.err(
                p.loc_of("power"),
                "a goniometric light with \"power\" needs an image that is not black",
            ));
        }
        k * power / (4.0 * PI * mean)
    } else {
        k
    };
    // pbrt-v4 swaps the light's y and z (its images have "up" along +z, its scenes along +y)
    let [x, y, z] = unit_axes(ctm);
    let frame = DMat4::from_cols(x, z, y, ctm.col(3));
    Ok(LightDesc {
        kind: LightKind::GoniometricMap {
            path,
            transform: vec![super::placed::matrix_step(&frame)],
        },
        spectrum: s.scaled((scale * k) as f32),
        sampling_weight: 1.0,
        loc,
    })
}
