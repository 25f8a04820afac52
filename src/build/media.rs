//! Media: their descriptions made render-ready (coefficients tabulated on a 1 nm grid over the
//! scene's wavelength range and checked there), and the media on either side of each shape.

use std::sync::Arc;

use crate::loader::LoadError;
use crate::loader::desc::{Coefficients, MediumDesc, MediumKind, SceneDesc, ShapeDesc, VolumeDesc};
use crate::medium::{Grid, Heterogeneous, Homogeneous, Medium, MediumInterface, Volume};
use crate::spectrum::{PiecewiseLinear, Spectrum, WavelengthRange};

/// The scene's media and the media on either side of each of its `surfaces` shapes. Media are
/// rendered by `path` alone so far: any other integrator is an error rather than a render that
/// ignores them.
pub(super) fn scene_media(
    desc: &SceneDesc,
    range: WavelengthRange,
    surfaces: usize,
) -> Result<(Vec<Medium>, Vec<MediumInterface>), LoadError> {
    let err =
        |m: &MediumDesc, field: String, msg: String| LoadError::new(&desc.path, m.loc, field, msg);
    let media = desc
        .media
        .iter()
        .map(|m| medium(m, range).map_err(|(f, e)| err(m, format!("media.{}.{f}", m.name), e)))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(m) = desc.media.first()
        && !matches!(
            desc.integrator.kind,
            crate::scene::IntegratorKind::Path
                | crate::scene::IntegratorKind::Light
                | crate::scene::IntegratorKind::Bdpt
        )
    {
        return Err(err(
            m,
            "integrator".into(),
            format!(
                "media (\"{}\") are rendered by the path, light and bdpt integrators only; {} would ignore them",
                m.name,
                desc.integrator.kind.name()
            ),
        ));
    }
    Ok((media, interfaces(desc, surfaces)))
}

/// A medium made render-ready; an error names the field and the wavelength where a coefficient is
/// negative or not finite, or an albedo leaves [0, 1].
fn medium(d: &MediumDesc, range: WavelengthRange) -> Result<Medium, (String, String)> {
    match &d.kind {
        MediumKind::Homogeneous {
            coefficients,
            phase,
            emission,
        } => {
            if let Some(e) = emission {
                check(e, range, "emission", f32::INFINITY)?;
            }
            let (sigma_t, albedo) = match coefficients {
                Coefficients::Extinction { sigma_t, albedo } => {
                    check(sigma_t, range, "sigma_t", f32::INFINITY)?;
                    if let VolumeDesc::Constant { value, .. } = albedo {
                        check(value, range, "albedo", 1.0)?;
                    }
                    (sigma_t.clone(), volume(albedo, range, "albedo")?.0)
                }
                Coefficients::AbsorptionScattering { sigma_a, sigma_s } => {
                    check(sigma_a, range, "sigma_a", f32::INFINITY)?;
                    check(sigma_s, range, "sigma_s", f32::INFINITY)?;
                    let t = |l: f32| sigma_a.eval(l) + sigma_s.eval(l);
                    let a = |l: f32| {
                        let t = t(l);
                        if t > 0.0 { sigma_s.eval(l) / t } else { 0.0 }
                    };
                    (tabulate(range, t), Volume::Constant(tabulate(range, a)))
                }
            };
            let absorbing = match &albedo {
                Volume::Constant(a) => grid(range).into_iter().all(|l| a.eval(l) == 0.0),
                Volume::Grid { .. } => false,
            };
            Ok(Medium::Homogeneous(Homogeneous {
                sigma_t,
                albedo,
                phase: *phase,
                emission: emission.clone(),
                absorbing,
            }))
        }
        MediumKind::Heterogeneous {
            density,
            albedo,
            scale,
            phase,
        } => {
            let (density, to_local, max) = volume(density, range, "sigma_t")?;
            let (albedo, _, _) = volume(albedo, range, "albedo")?;
            let scale = *scale as f32;
            Ok(Medium::Heterogeneous(Heterogeneous {
                density,
                albedo,
                scale,
                phase: *phase,
                to_local,
                // a margin over the bound for the rounding of interpolation
                majorant: scale * max * (1.0 + 1e-5),
            }))
        }
    }
}

/// A volume, the map from world space to its frame, and the largest value it takes.
fn volume(
    d: &VolumeDesc,
    range: WavelengthRange,
    field: &str,
) -> Result<(Volume, glam::Mat4, f32), (String, String)> {
    let place = |steps| {
        super::shapes::steps(steps, 1.0, false)
            .map(|t| t.inverse_matrix())
            .map_err(|e| (format!("{field}.to_world"), e))
    };
    match d {
        VolumeDesc::Constant { value, to_world } => {
            check(value, range, field, f32::INFINITY)?;
            let max = grid(range)
                .into_iter()
                .map(|l| value.eval(l))
                .fold(0.0, f32::max);
            Ok((Volume::Constant(value.clone()), place(to_world)?, max))
        }
        VolumeDesc::Grid {
            res,
            channels,
            values,
            wrap,
            to_world,
            file,
        } => {
            let g = Grid::new(*res, *channels, values, *wrap)
                .map_err(|e| (field.to_string(), format!("{}: {e}", file.display())))?;
            let max = g.max();
            let to_local = place(to_world)?;
            Ok((
                Volume::Grid {
                    grid: Arc::new(g),
                    to_local,
                },
                to_local,
                max,
            ))
        }
    }
}

/// The media on either side of each shape of the scene (groups' shapes have none), or an
/// empty table for a scene without media.
fn interfaces(desc: &SceneDesc, surfaces: usize) -> Vec<MediumInterface> {
    if desc.media.is_empty() {
        return Vec::new();
    }
    let of = |s: &ShapeDesc| MediumInterface {
        interior: s.interior.map(|m| m as u32),
        exterior: s.exterior.map(|m| m as u32),
    };
    let mut v: Vec<MediumInterface> = desc.shapes.iter().map(of).collect();
    v.resize(surfaces, MediumInterface::default());
    v
}

/// Every whole nanometre of the range (and its ends).
fn grid(range: WavelengthRange) -> Vec<f32> {
    let (lo, hi) = (range.min_nm, range.max_nm);
    let mut v = vec![lo];
    let mut l = lo.floor() + 1.0;
    while l < hi {
        v.push(l);
        l += 1.0;
    }
    if hi > lo {
        v.push(hi);
    }
    v
}

fn tabulate(range: WavelengthRange, f: impl Fn(f32) -> f32) -> Spectrum {
    let lambda = grid(range);
    let value = lambda.iter().map(|&l| f(l)).collect();
    match PiecewiseLinear::new(lambda, value) {
        Ok(t) => Spectrum::Piecewise(Arc::new(t)),
        // a range of one wavelength: its value
        Err(_) => Spectrum::Constant(f(range.min_nm)),
    }
}

/// Checks `s` at every nanometre of the range: finite, at least 0 and at most `max`.
fn check(
    s: &Spectrum,
    range: WavelengthRange,
    field: &str,
    max: f32,
) -> Result<(), (String, String)> {
    for l in grid(range) {
        let v = s.eval(l);
        if !v.is_finite() || v < 0.0 || v > max {
            let why = if max.is_finite() && v > max {
                format!("must be at most {max}")
            } else {
                "must be finite and not negative".to_string()
            };
            return Err((field.to_string(), format!("is {v} at {l} nm; it {why}")));
        }
    }
    Ok(())
}
