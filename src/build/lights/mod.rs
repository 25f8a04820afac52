//! Lights: the exact physical scale of each light from what the scene file says.
//!
//! Each light is a spectral shape S(λ) times a scale k. With the band integral
//! B = ∫ S dλ over the film's wavelength range and the luminous integral
//! V = K_m ∫ S ȳ dλ over the same range (`../shared/PHYSICS.md`, "Photometric units"):
//!
//! | given | k |
//! | --- | --- |
//! | radiance L (W·m⁻²·sr⁻¹), intensity I (W/sr), irradiance E (W/m²) | L/B, I/B, E/B |
//! | luminance (cd/m²), luminous intensity (cd), illuminance (lx) | value / V |
//! | point power Φ (W or lm) | Φ/(4π B) or Φ/(4π V) |
//! | spot power | Φ/(Ω B), Ω = 2π[(1 − cos θ_start) + (cos θ_start − cos θ_total)/2] |
//! | area power | Φ/(π A B), two-sided Φ/(2π A B) (Φ = π L A) |
//! | beam power Φ (W or lm) | Φ/B or Φ/V (spread over the beam's disk) |
//! | luminaire file (candela table T, ∫ T dω = F lm) | t/V per cd (t the tilt factor); `scale` s: s·t/V; power Φ: Φ/(F V) or Φ/(F B) |
//! | scale s | s (S is already absolute) |
//! | environment map: mean radiance L̄ or luminance L̄_v over the sphere | 4π L̄ / ∫∫ M dλ dω or 4π L̄_v / (K_m ∫∫ M ȳ dλ dω), M the map under S |
//!
//! An environment map's S is the illuminant of an RGB (1, 1, 1) pixel: Mitsuba's normalised
//! D65 for Mitsuba files (as its `envmap`), and for TOML files D65 of luminance 1 cd/m², so that
//! `scale` s makes such a pixel s cd/m².
//!
//! **Watts and lumens count the film's wavelength range only.** B and V are integrals over that
//! range, so a spectrum with power outside it gets a different k when the range changes. For a
//! 100 W `cie-a` point light (S_A is Planck's law, non-zero at every λ): B = 59 942 nm over
//! 360–830 nm and 47 179 nm over 380–780 nm, so its spectral intensity, its luminous intensity
//! and its lumens (12 294 lm vs 15 620 lm) are 1.2705× larger over the narrower range. A
//! photometric amount fixes V instead, which does not change while the range holds 360–830 nm
//! (ȳ is zero outside). `tests/light_power.rs`
//! (`named_illuminants_band_radiance_and_lumens_over_the_range`) checks both against closed forms.

mod octahedral;
mod scale;
mod sources;

use glam::Vec3;

use super::{surface, v3};
use crate::geometry::Frame;
use crate::geometry::shape::Shape;
use crate::light::BeamSection as Section;
use crate::light::{
    AreaLight, BeamLight, DirectionalLight, EnvironmentLight, Light, PointLight, ProjectorLight,
    SpotLight, SpotTexture,
};
use crate::loader::desc::{
    BeamSection, DirectionalAmount, EmitAmount, LightKind, PointAmount, SceneDesc,
};
use crate::loader::{LoadError, Loc};
use crate::scene::Surface;
use crate::spectrum::WavelengthRange;
use crate::units::{illuminance, irradiance, plain};

use crate::light::SpotFalloff;
use crate::loader::desc::{LightDesc, Point, TextureDesc, TransformStep};
use crate::units::Angle;
use scale::*;
use sources::*;

/// The lights, their sampling weights and the surfaces table, as [`lights`] returns them.
type Lights = (Vec<Light>, Vec<f64>, Vec<Surface>);

/// All lights (scene lights, then one area light per emitting shape), their sampling weights
/// ([`crate::loader::desc::LightDesc::sampling_weight`]) and the surfaces table.
pub(super) fn lights(
    desc: &SceneDesc,
    shapes: &[Shape],
    r: WavelengthRange,
) -> Result<Lights, LoadError> {
    let err = |loc: Loc, field: String, msg: String| LoadError::new(&desc.path, loc, field, msg);
    let mut lights = Vec::new();
    for (i, l) in desc.lights.iter().enumerate() {
        let light = light(l, r).map_err(|m| err(l.loc, format!("lights[{i}]"), m))?;
        lights.push(light);
    }
    let mut weights: Vec<f64> = desc.lights.iter().map(|l| l.sampling_weight).collect();
    let mut surfaces = Vec::with_capacity(shapes.len());
    for (i, (s, shape)) in desc.shapes.iter().zip(shapes).enumerate() {
        let mut light = None;
        if let Some(em) = &s.emission {
            let area = shape.area() as f64;
            let field = format!("shapes[{i}].emission");
            if !(area > 0.0) {
                return Err(err(em.loc, field, "the emitter has zero area".into()));
            }
            let sides = if em.two_sided { 2.0 } else { 1.0 };
            let (per, g) = emit(&em.amount, Some(sides * std::f64::consts::PI * area))
                .map_err(|m| err(em.loc, field.clone(), m))?;
            let radiance = match &em.texture {
                None => crate::texture::Texture::Uniform(
                    scaled(&em.spectrum, per, g, r).map_err(|m| err(em.loc, field.clone(), m))?,
                ),
                Some(t) => {
                    if !matches!(em.amount, EmitAmount::Scale(k) if k == 1.0) {
                        return Err(err(
                            em.loc,
                            field,
                            "a textured radiance is read as given (Mitsuba's); it takes no power, luminance or scale".into(),
                        ));
                    }
                    // read as Mitsuba 3.9.1 reads a bitmap radiance (measured): as a
                    // reflectance image is read, without an illuminant shape (grey texels kept,
                    // colour texels clamped to [0, 1]), in W·m⁻²·sr⁻¹·nm⁻¹
                    super::textures::texture(t).map_err(|m| err(em.loc, field.clone(), m))?
                }
            };
            light = Some(lights.len());
            lights.push(Light::Area(AreaLight {
                shape: i as u32,
                radiance,
                two_sided: em.two_sided,
                invisible: matches!(
                    &s.alpha,
                    Some(TextureDesc::Uniform(crate::spectrum::Spectrum::Constant(a))) if *a <= 0.0
                ),
            }));
            weights.push(em.sampling_weight);
        }
        surfaces.push(surface(s.material, s.two_sided, light));
    }
    Ok((lights, weights, surfaces))
}

/// The render-side light for one scene light, at its physical scale over `r`.
fn light(l: &LightDesc, r: WavelengthRange) -> Result<Light, String> {
    Ok(match &l.kind {
        LightKind::Point { position, amount } => {
            let (per, g) = point_amount(amount, 4.0 * std::f64::consts::PI);
            Light::Point(PointLight {
                position: v3(position),
                intensity: scaled(&l.spectrum, per, g, r)?,
            })
        }
        LightKind::Spot {
            position,
            target,
            cone_angle,
            falloff_start,
            falloff,
            amount,
            texture,
        } => spot(
            l,
            (position, target),
            cone_angle,
            falloff_start,
            falloff,
            amount,
            texture,
            r,
        )?,
        LightKind::Directional {
            direction,
            angular_diameter,
            amount,
        } => {
            let d = Vec3::new(
                direction[0] as f32,
                direction[1] as f32,
                direction[2] as f32,
            )
            .normalize();
            let per = match amount {
                DirectionalAmount::Irradiance(x) => {
                    Per::Band(x.get::<irradiance::watt_per_square_meter>())
                }
                DirectionalAmount::Illuminance(x) => Per::Luminous(x.get::<illuminance::lux>()),
                DirectionalAmount::Scale(s) => Per::Scale(*s),
            };
            let alpha = plain::radians(*angular_diameter) as f64 / 2.0;
            Light::Directional(DirectionalLight::new(
                d,
                scaled(&l.spectrum, per, 1.0, r)?,
                alpha,
            ))
        }
        LightKind::Beam {
            position,
            target,
            section,
            amount,
        } => beam(l, (position, target), section, amount, r)?,
        LightKind::Projector {
            transform,
            fov,
            fov_axis,
            image,
            constant_intensity,
        } => projector(l, transform, (fov, *fov_axis), image, *constant_intensity)?,
        LightKind::Luminaire {
            position,
            target,
            c0,
            tilt,
            photometry,
            amount,
        } => Light::Goniometric(Box::new(luminaire(
            (v3(position), v3(target), *c0),
            tilt.get::<crate::units::angle::degree>(),
            photometry,
            amount,
            &l.spectrum,
            r,
        )?)),
        LightKind::Sky {
            model,
            sun,
            up,
            amount,
        } => Light::EnvMap(Box::new(sky(*model, *sun, *up, amount, &l.spectrum, r)?)),
        LightKind::Environment { amount } => {
            let (per, g) = emit(amount, None)?;
            Light::Environment(EnvironmentLight {
                radiance: scaled(&l.spectrum, per, g, r)?,
            })
        }
        LightKind::EnvMap {
            path,
            transform,
            amount,
        } => Light::EnvMap(Box::new(envmap(path, transform, amount, &l.spectrum, r)?)),
        LightKind::GoniometricMap { path, transform } => Light::GoniometricMap(Box::new(
            octahedral::goniometric_map(path, transform, &l.spectrum)?,
        )),
        LightKind::OctahedralMap {
            path,
            transform,
            amount,
        } => Light::Octahedral(Box::new(octahedral::octahedral(
            path,
            transform,
            amount,
            &l.spectrum,
            r,
        )?)),
    })
}

/// A spot light, its intensity set by `amount` over its cone, its optional texture placed.
#[allow(clippy::too_many_arguments)]
fn spot(
    l: &LightDesc,
    (position, target): (&Point, &Point),
    cone_angle: &Angle,
    falloff_start: &Angle,
    falloff: &SpotFalloff,
    amount: &PointAmount,
    texture: &Option<Box<(TextureDesc, Vec<TransformStep>)>>,
    r: WavelengthRange,
) -> Result<Light, String> {
    let p = v3(position);
    let axis = (v3(target) - p).normalize();
    let mut spot = SpotLight::new(
        p,
        axis,
        plain::radians(*falloff_start),
        plain::radians(*cone_angle),
        *falloff,
    );
    let (per, g) = point_amount(amount, spot.solid_angle_factor());
    spot.intensity = scaled(&l.spectrum, per, g, r)?;
    if let Some(t) = texture {
        let (image, steps) = t.as_ref();
        let m = glam::Mat3::from_mat4(super::shapes::steps(steps, 1.0, false)?.matrix());
        let frame = glam::Mat3::from_cols(
            m.x_axis.normalize(),
            m.y_axis.normalize(),
            m.z_axis.normalize(),
        );
        spot.texture = Some(Box::new(SpotTexture {
            image: super::textures::texture(image)?,
            frame,
            tan_total: plain::radians(*cone_angle).tan(),
        }));
    }
    Ok(Light::Spot(spot))
}

/// The position and orthonormal frame (columns) of a rigid `transform`; None if it scales or
/// shears, or is not a transform.
pub(super) fn rigid(transform: &[TransformStep]) -> Option<(Vec3, glam::Mat3)> {
    let t = super::shapes::steps(transform, 1.0, false).ok()?;
    let m = glam::Mat3::from_mat4(t.matrix());
    (m.transpose() * m - glam::Mat3::IDENTITY)
        .to_cols_array()
        .iter()
        .all(|x| x.abs() < 1e-4)
        .then(|| (t.point(Vec3::ZERO), m))
}

/// A projector: an image thrown through a pinhole of field of view `fov` (across `fov_axis`),
/// placed by a rigid `transform`, with Mitsuba's law or, `constant_intensity`, pbrt-v4's.
fn projector(
    l: &LightDesc,
    transform: &[TransformStep],
    (fov, fov_axis): (&Angle, crate::loader::desc::FovAxis),
    image: &TextureDesc,
    constant_intensity: bool,
) -> Result<Light, String> {
    use crate::loader::desc::FovAxis;
    let (position, m) = rigid(transform).ok_or_else(|| {
        "a projector's to_world must be a rotation and a translation (no scale)".to_string()
    })?;
    let image = super::textures::texture(image)?;
    let (w, h) = match &image {
        crate::texture::Texture::Bitmap(b) => b.resolution(),
        _ => (1, 1),
    };
    let aspect = w as f32 / h as f32;
    let tan = (plain::radians(*fov) / 2.0).tan();
    let along_y = match fov_axis {
        FovAxis::X => false,
        FovAxis::Y => true,
        FovAxis::Larger => aspect < 1.0,
        FovAxis::Smaller => aspect > 1.0,
    };
    let (tan_x, tan_y) = if along_y {
        (tan * aspect, tan)
    } else {
        (tan, tan / aspect)
    };
    Ok(Light::Projector(Box::new(ProjectorLight {
        position,
        frame: m,
        tan_x,
        tan_y,
        image,
        spectrum: l.spectrum.clone(),
        law: if constant_intensity {
            crate::light::ProjectorLaw::Intensity
        } else {
            crate::light::ProjectorLaw::PlaneIrradiance
        },
    })))
}

/// A beam light: its frame (a slit's sides along its `up` and across) and section.
fn beam(
    l: &LightDesc,
    (position, target): (&Point, &Point),
    section: &BeamSection,
    amount: &PointAmount,
    r: WavelengthRange,
) -> Result<Light, String> {
    let p = v3(position);
    let (per, _) = point_amount(amount, 1.0);
    let n = (v3(target) - p).normalize();
    let (frame, section) = match section {
        BeamSection::Disk(radius) => (
            Frame::from_normal(n),
            Section::Disk {
                radius: plain::metres(*radius),
            },
        ),
        BeamSection::Slit { width, height, up } => {
            // the loader made `up` a unit vector across the beam
            let t = Vec3::new(up[0] as f32, up[1] as f32, up[2] as f32).normalize();
            let s = t.cross(n).normalize();
            (
                Frame { s, t, n },
                Section::Rect {
                    half_s: 0.5 * plain::metres(*width),
                    half_t: 0.5 * plain::metres(*height),
                },
            )
        }
    };
    Ok(Light::Beam(BeamLight {
        center: p,
        frame,
        section,
        power: scaled(&l.spectrum, per, 1.0, r)?,
    }))
}
