//! pbrt-v4's `AreaLightSource "diffuse"` (`DiffuseAreaLight::Create`, src/pbrt/lights.cpp):
//! the state it sets for the shapes after it, and the emission it gives each of them.

use super::params::{Params, R};
use super::{Reader, spectra};
use crate::loader::Loc;
use crate::loader::desc::{EmissionDesc, EmitAmount, TextureDesc, TransformStep};
use crate::spectrum::Spectrum;
use crate::texture::TexFilter;

/// An `AreaLightSource "diffuse"`: its emitted radiance (W·m⁻²·sr⁻¹·nm⁻¹ per unit of pbrt's
/// spectrum, see [`spectra::illuminant`]) and whether both sides emit.
#[derive(Clone, Debug)]
pub(super) struct AreaLight {
    pub spectrum: Spectrum,
    pub scale: f64,
    pub two_sided: bool,
    /// pbrt-v4's `power` (∫ȳ·Φ dλ of each shape, each triangle of a mesh), if given; with an
    /// image, already divided by the image's mean luminance (linear sRGB), as pbrt-v4 does.
    pub power: Option<f64>,
    /// An image over the surface's uv (`filename`), whose texels' `RGBIlluminantSpectrum`
    /// uplift `spectrum` × `scale` multiplies.
    pub image: Option<std::path::PathBuf>,
    pub loc: Loc,
}

/// An `AreaLightSource`: `L` or an image `filename` over the surface's uv (looked up at
/// (u, 1 − v), bilinear, clamped, each texel's RGB an `RGBIlluminantSpectrum`; pbrt-v4's
/// `DiffuseAreaLight`), `scale`, `twosided`, `power` (with an image, over its mean luminance).
pub(super) fn area_light(kind: &str, p: &Params, loc: Loc, r: &Reader) -> R<AreaLight> {
    if kind != "diffuse" {
        return Err(p.err(
            loc,
            format!("the area light \"{kind}\" is not read (pbrt-v4 has only \"diffuse\")"),
        ));
    }
    let image = match p.string("filename")? {
        None => None,
        Some(name) => {
            if let Some(q) = p.get("L") {
                return Err(p.err(
                    q.loc,
                    "an area light takes \"L\" or \"filename\", not both (pbrt-v4)",
                ));
            }
            let path = r.resolve(&r.root, &name);
            if !path.is_file() {
                return Err(p.err(
                    p.loc_of("filename"),
                    format!("no image \"{}\"", path.display()),
                ));
            }
            Some(path)
        }
    };
    // without `L`, the colour space's illuminant of luminance 1 (k = 1)
    let (spectrum, k) = spectra::illuminant(p, "L")?;
    let power = p.float("power", -1.0)?;
    // with an image, `power` is over its mean luminance (read only when asked for)
    let power = match &image {
        Some(path) if power > 0.0 => {
            let (rgb, _) = super::lights::light_image(p, path)?;
            let n = rgb.len().max(1) as f64;
            let mean = rgb
                .iter()
                .map(|c| super::lights::luminance(*c))
                .sum::<f64>()
                / n;
            if !(mean > 0.0) {
                return Err(p.err(
                    p.loc_of("power"),
                    "an area light with \"power\" needs an image that is not black",
                ));
            }
            power / mean
        }
        _ => power,
    };
    Ok(AreaLight {
        spectrum,
        scale: p.float("scale", 1.0)? * k,
        two_sided: p.bool("twosided", false)?,
        power: (power > 0.0).then_some(power),
        image,
        loc,
    })
}

/// An area light's emission at `k` times its spectrum: uniform, or its image (pbrt-v4's
/// lookup at (u, 1 − v), bilinear, clamped; each texel an unbounded uplift) times the spectrum.
pub(super) fn emission(a: &AreaLight, k: f64) -> EmissionDesc {
    let (texture, amount) = match &a.image {
        None => (None, EmitAmount::Scale(k)),
        Some(path) => {
            // pbrt-v4 looks the image up at (u, 1 − v), bilinear
            let flip_v = vec![TransformStep::Matrix([
                1.0, 0.0, 0.0, 0.0, //
                0.0, -1.0, 0.0, 1.0, //
                0.0, 0.0, 1.0, 0.0, //
                0.0, 0.0, 0.0, 1.0,
            ])];
            let image =
                super::lights::light_texture(path.clone(), TexFilter::Bilinear, flip_v, a.loc);
            let spectrum = TextureDesc::Uniform(a.spectrum.scaled(k as f32));
            let texture = TextureDesc::Scaled(Box::new([image, spectrum]));
            (Some(texture), EmitAmount::Scale(1.0))
        }
    };
    EmissionDesc {
        spectrum: a.spectrum.clone(),
        texture,
        amount,
        two_sided: a.two_sided,
        sampling_weight: 1.0,
        loc: a.loc,
    }
}
