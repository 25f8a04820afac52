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

use glam::Vec3;

use super::{surface, v3};
use crate::colour::cie::{K_M, cmf};
use crate::geometry::Frame;
use crate::geometry::shape::Shape;
use crate::light::{
    AreaLight, BeamLight, DirectionalLight, EnvMapLight, EnvironmentLight, Fold, GoniometricLight,
    IntensityTable, Light, PointLight, ProjectorLight, SpotLight, SpotTexture,
};
use crate::loader::desc::SkyAmount;
use crate::loader::desc::{
    DirectionalAmount, EmitAmount, EnvMapAmount, LightKind, LuminaireAmount, PointAmount, SceneDesc,
};
use crate::loader::photometric::{Photometry, Symmetry};
use crate::loader::{LoadError, Loc};
use crate::scene::Surface;
use crate::spectrum::{Spectrum, WavelengthRange};
use crate::units::{
    illuminance, irradiance, luminance, luminous_flux, luminous_intensity, plain, power, radiance,
    radiant_intensity,
};

/// ∫ S dλ over the range, in S's unit × nm. Power outside the range is not counted: a radiometric
/// amount (W, W/sr, W/m², W/m²/sr) is the power *within* the range.
pub fn band_integral(s: &Spectrum, r: WavelengthRange) -> f64 {
    s.integrate(r.min_nm, r.max_nm, 1.0)
}

/// K_m ∫ S ȳ dλ over the range ∩ 360–830 nm, lm per (W per S's unit). Light of the spectrum
/// outside the range is not counted.
pub fn luminous_integral(s: &Spectrum, r: WavelengthRange) -> f64 {
    K_M * s.integrate_weighted(r.min_nm.max(360.0), r.max_nm.min(830.0), 1.0, |l| {
        cmf().y_bar(l) as f64
    })
}

enum Per {
    /// Radiometric: divide by the band integral.
    Band(f64),
    /// Photometric: divide by the luminous integral.
    Luminous(f64),
    Scale(f64),
}

fn scaled(s: &Spectrum, per: Per, geometry: f64, r: WavelengthRange) -> Result<Spectrum, String> {
    let k = match per {
        Per::Band(v) => {
            let b = band_integral(s, r) * geometry;
            if !(b > 0.0) {
                return Err(format!(
                    "the spectrum carries no power in {}–{} nm",
                    r.min_nm, r.max_nm
                ));
            }
            v / b
        }
        Per::Luminous(v) => {
            let l = luminous_integral(s, r) * geometry;
            if !(l > 0.0) {
                return Err("the spectrum has no visible light, so a photometric amount cannot set its scale".into());
            }
            v / l
        }
        Per::Scale(v) => v,
    };
    if !k.is_finite() || k as f32 == f32::INFINITY {
        return Err(format!("the light's scale ({k}) is not representable"));
    }
    Ok(s.scaled(k as f32))
}

fn emit(amount: &EmitAmount, area_factor: Option<f64>) -> Result<(Per, f64), String> {
    Ok(match amount {
        EmitAmount::Radiance(l) => (
            Per::Band(l.get::<radiance::watt_per_square_meter_steradian>()),
            1.0,
        ),
        EmitAmount::Luminance(l) => (
            Per::Luminous(l.get::<luminance::candela_per_square_meter>()),
            1.0,
        ),
        EmitAmount::Power(p) => (
            Per::Band(p.get::<power::watt>()),
            area_factor.ok_or("power needs an area")?,
        ),
        EmitAmount::LuminousFlux(f) => (
            Per::Luminous(f.get::<luminous_flux::lumen>()),
            area_factor.ok_or("power needs an area")?,
        ),
        EmitAmount::Scale(s) => (Per::Scale(*s), 1.0),
    })
}

fn point_amount(a: &PointAmount, solid_angle: f64) -> (Per, f64) {
    match a {
        PointAmount::Power(p) => (Per::Band(p.get::<power::watt>()), solid_angle),
        PointAmount::LuminousFlux(f) => {
            (Per::Luminous(f.get::<luminous_flux::lumen>()), solid_angle)
        }
        PointAmount::Intensity(i) => (
            Per::Band(i.get::<radiant_intensity::watt_per_steradian>()),
            1.0,
        ),
        PointAmount::LuminousIntensity(i) => {
            (Per::Luminous(i.get::<luminous_intensity::candela>()), 1.0)
        }
        PointAmount::Scale(s) => (Per::Scale(*s), 1.0),
    }
}

/// An environment map: the image read (8- and 16-bit files decoded from sRGB, as Mitsuba
/// does), its rotation, and its illuminant scaled by `amount`: `Scale(k)` multiplies it;
/// `Radiance(L)` and `Luminance(Lv)` set the mean over the sphere, 1/(4π) ∫ L dω, of the band
/// radiance or of the luminance K_m ∫ L ȳ dλ; `Irradiance(E)` and `Illuminance(Ev)` set
/// ∫ L cos θ dω (band, or K_m ∫ ȳ) on a plane facing the map's zenith.
fn envmap(
    path: &std::path::Path,
    transform: &[crate::loader::desc::TransformStep],
    amount: &EnvMapAmount,
    illuminant: &Spectrum,
    r: WavelengthRange,
) -> Result<EnvMapLight, String> {
    let img = crate::image_io::read_rgb(path).map_err(|e| e.to_string())?;
    let rgb: Vec<[f32; 3]> = if img.encoding == crate::image_io::Encoding::Srgb {
        img.rgb
            .iter()
            .map(|p| p.map(super::textures::srgb_to_linear))
            .collect()
    } else {
        img.rgb
    };
    let m = super::shapes::steps(transform, 1.0, false)?.matrix();
    let rot = glam::Mat3::from_mat4(m);
    envmap_of(img.width, img.height, &rgb, rot, amount, illuminant, r)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// An environment map from linear RGB pixels (see [`envmap`]).
fn envmap_of(
    width: usize,
    height: usize,
    rgb: &[[f32; 3]],
    rot: glam::Mat3,
    amount: &EnvMapAmount,
    illuminant: &Spectrum,
    r: WavelengthRange,
) -> Result<EnvMapLight, String> {
    let at = |s: Spectrum| EnvMapLight::new(width, height, rgb, s, rot);
    let unit = at(illuminant.clone())?;
    let four_pi = 4.0 * std::f64::consts::PI;
    let visible = WavelengthRange {
        min_nm: r.min_nm.max(360.0),
        max_nm: r.max_nm.min(830.0),
    };
    let y_bar = |l: f32| cmf().y_bar(l) as f64;
    // cos θ on a plane facing the map's zenith
    let zenith = rot.mul_vec3(glam::Vec3::Y).normalize();
    let cosine = |d: glam::Vec3| d.dot(zenith).max(0.0) as f64;
    let k = match amount {
        EnvMapAmount::Scale(k) => *k,
        EnvMapAmount::Radiance(l) => {
            let b = unit.band_radiant_exitance(r) / four_pi;
            l.get::<radiance::watt_per_square_meter_steradian>() / b
        }
        EnvMapAmount::Luminance(lv) => {
            let y = K_M * unit.weighted_integral(visible, y_bar) / four_pi;
            lv.get::<luminance::candela_per_square_meter>() / y
        }
        EnvMapAmount::Irradiance(e) => {
            let b = unit.integral_where(r, &|_| 1.0, cosine);
            e.get::<irradiance::watt_per_square_meter>() / b
        }
        EnvMapAmount::Illuminance(ev) => {
            let y = K_M * unit.integral_where(visible, &y_bar, cosine);
            ev.get::<illuminance::lux>() / y
        }
    };
    if !(k.is_finite() && k >= 0.0) {
        return Err(format!(
            "the environment map's scale ({k}) is not a finite number ≥ 0 (is the image black?)"
        ));
    }
    at(illuminant.scaled(k as f32))
}

/// A CIE sky baked into a 1024 × 513 latitude–longitude map (the horizon on row 256, the
/// zenith on row 0) whose grey pixels are L/L_z, under the illuminant S/(K_m ∫ S ȳ dλ) (one
/// pixel unit = 1 cd/m²), the map's +y turned to `up`; scaled to the zenith luminance, or to
/// the horizontal illuminance or irradiance of the bilinear map itself. Bilinear
/// interpolation errs by O(1/512²) (measured in `tests/daylight.rs`).
fn sky(
    model: crate::daylight::sky::SkyModel,
    sun: [f64; 3],
    up: [f64; 3],
    amount: &SkyAmount,
    spectrum: &Spectrum,
    r: WavelengthRange,
) -> Result<EnvMapLight, String> {
    let (w, h) = (1024usize, 513usize);
    let upv = glam::DVec3::from_array(up).normalize();
    let sunv = glam::DVec3::from_array(sun).normalize();
    let x = upv.any_orthonormal_vector();
    let z = x.cross(upv);
    let rot = glam::DMat3::from_cols(x, upv, z);
    let zs = sunv.dot(upv).clamp(-1.0, 1.0).acos();
    let mut rgb = Vec::with_capacity(w * h);
    for j in 0..h {
        let theta = std::f64::consts::PI * j as f64 / (h - 1) as f64;
        for i in 0..w {
            let u = 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / w as f64;
            let d =
                rot * glam::DVec3::new(theta.sin() * u.sin(), theta.cos(), -theta.sin() * u.cos());
            let chi = d.dot(sunv).clamp(-1.0, 1.0).acos();
            let v = if j * 2 > h - 1 {
                0.0
            } else {
                model.relative_luminance(theta.min(std::f64::consts::FRAC_PI_2), chi, zs)
            };
            rgb.push([v as f32; 3]);
        }
    }
    let v = luminous_integral(spectrum, r);
    if !(v > 0.0) {
        return Err(
            "the spectrum has no visible light, so a luminance cannot set its scale".into(),
        );
    }
    let illuminant = spectrum.scaled((1.0 / v) as f32);
    let amount = match amount {
        SkyAmount::ZenithLuminance(l) => {
            EnvMapAmount::Scale(l.get::<luminance::candela_per_square_meter>())
        }
        SkyAmount::HorizontalIlluminance(e) => EnvMapAmount::Illuminance(*e),
        SkyAmount::HorizontalIrradiance(e) => EnvMapAmount::Irradiance(*e),
    };
    envmap_of(w, h, &rgb, rot.as_mat3(), &amount, &illuminant, r)
}

/// A luminaire: the photometric frame from the nadir (`position` → `target`) and the C0
/// direction, the table in plain `f32`, and the spectrum per candela scaled as `amount` says
/// (see the table in the module doc).
fn luminaire(
    (position, target, c0): (Vec3, Vec3, Option<[f64; 3]>),
    tilt_deg: f64,
    p: &Photometry,
    amount: &LuminaireAmount,
    spectrum: &Spectrum,
    r: WavelengthRange,
) -> Result<GoniometricLight, String> {
    let Some(up) = (position - target).try_normalize() else {
        return Err("the target is too close to the position to aim the luminaire".into());
    };
    let c0 = match c0 {
        Some(d) => Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32),
        // world +x, or +z when the nadir is within 25° of the x axis
        None if up.x.abs() > 25f32.to_radians().cos() => Vec3::Z,
        None => Vec3::X,
    };
    let Some(x) = (c0 - up * c0.dot(up)).try_normalize() else {
        return Err("the C0 direction is along the nadir".into());
    };
    let frame = glam::Mat3::from_cols(x, up.cross(x), up);
    let table = IntensityTable {
        vertical: p.vertical_deg.iter().map(|&a| a as f32).collect(),
        horizontal: p.horizontal_deg.iter().map(|&a| a as f32).collect(),
        fold: match p.symmetry {
            Symmetry::Axial => Fold::Axial,
            Symmetry::Quadrant => Fold::Quadrant,
            Symmetry::Bilateral0To180 => Fold::Bilateral0To180,
            Symmetry::Bilateral90To270 => Fold::Bilateral90To270,
            Symmetry::Full => Fold::Full,
        },
        cd: p.candela.iter().map(|&c| c as f32).collect(),
    };
    let flux = table.luminous_flux();
    if !(flux > 0.0) {
        return Err(format!(
            "{}: the luminaire emits nothing (every intensity is 0)",
            p.file.display()
        ));
    }
    let v = luminous_integral(spectrum, r);
    if !(v > 0.0) {
        return Err(
            "the spectrum has no visible light, so the file's candela cannot set its scale".into(),
        );
    }
    let tilt = p.tilt_factor(tilt_deg);
    let k = match amount {
        LuminaireAmount::File => tilt / v,
        LuminaireAmount::Scale(s) => s * tilt / v,
        LuminaireAmount::LuminousFlux(f) => f.get::<luminous_flux::lumen>() / (flux * v),
        LuminaireAmount::Power(w) => {
            let b = band_integral(spectrum, r);
            if !(b > 0.0) {
                return Err(format!(
                    "the spectrum carries no power in {}–{} nm",
                    r.min_nm, r.max_nm
                ));
            }
            w.get::<power::watt>() / (flux * b)
        }
    };
    if !(k.is_finite() && (k as f32).is_finite()) {
        return Err(format!("the luminaire's scale ({k}) is not representable"));
    }
    GoniometricLight::new(position, frame, spectrum.scaled(k as f32), table)
        .ok_or_else(|| "the luminaire emits nothing".into())
}

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
        let field = format!("lights[{i}]");
        let e = |m: String| err(l.loc, field.clone(), m);
        let light = match &l.kind {
            LightKind::Point { position, amount } => {
                let (per, g) = point_amount(amount, 4.0 * std::f64::consts::PI);
                Light::Point(PointLight {
                    position: v3(position),
                    intensity: scaled(&l.spectrum, per, g, r).map_err(e)?,
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
            } => {
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
                spot.intensity = scaled(&l.spectrum, per, g, r).map_err(e)?;
                if let Some(t) = texture {
                    let (image, steps) = t.as_ref();
                    let m = glam::Mat3::from_mat4(
                        super::shapes::steps(steps, 1.0, false).map_err(e)?.matrix(),
                    );
                    let frame = glam::Mat3::from_cols(
                        m.x_axis.normalize(),
                        m.y_axis.normalize(),
                        m.z_axis.normalize(),
                    );
                    spot.texture = Some(Box::new(SpotTexture {
                        image: super::textures::texture(image).map_err(e)?,
                        frame,
                        tan_total: plain::radians(*cone_angle).tan(),
                    }));
                }
                Light::Spot(spot)
            }
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
                    scaled(&l.spectrum, per, 1.0, r).map_err(e)?,
                    alpha,
                ))
            }
            LightKind::Beam {
                position,
                target,
                radius,
                amount,
            } => {
                let p = v3(position);
                let (per, _) = point_amount(amount, 1.0);
                Light::Beam(BeamLight {
                    center: p,
                    frame: Frame::from_normal((v3(target) - p).normalize()),
                    radius: plain::metres(*radius),
                    power: scaled(&l.spectrum, per, 1.0, r).map_err(e)?,
                })
            }
            LightKind::Projector {
                transform,
                fov,
                fov_axis_y,
                image,
            } => {
                let t = super::shapes::steps(transform, 1.0, false).map_err(e)?;
                let m = glam::Mat3::from_mat4(t.matrix());
                let rigid = (m.transpose() * m - glam::Mat3::IDENTITY)
                    .to_cols_array()
                    .iter()
                    .all(|x| x.abs() < 1e-4);
                if !rigid {
                    return Err(e(
                        "a projector's to_world must be a rotation and a translation (no scale)"
                            .into(),
                    ));
                }
                let image = super::textures::texture(image).map_err(e)?;
                let (w, h) = match &image {
                    crate::texture::Texture::Bitmap(b) => b.resolution(),
                    _ => (1, 1),
                };
                let aspect = w as f32 / h as f32;
                let tan = (plain::radians(*fov) / 2.0).tan();
                let (tan_x, tan_y) = if *fov_axis_y {
                    (tan * aspect, tan)
                } else {
                    (tan, tan / aspect)
                };
                Light::Projector(Box::new(ProjectorLight {
                    position: t.point(Vec3::ZERO),
                    frame: m,
                    tan_x,
                    tan_y,
                    image,
                    spectrum: l.spectrum.clone(),
                }))
            }
            LightKind::Luminaire {
                position,
                target,
                c0,
                tilt,
                photometry,
                amount,
            } => Light::Goniometric(Box::new(
                luminaire(
                    (v3(position), v3(target), *c0),
                    tilt.get::<crate::units::angle::degree>(),
                    photometry,
                    amount,
                    &l.spectrum,
                    r,
                )
                .map_err(e)?,
            )),
            LightKind::Sky {
                model,
                sun,
                up,
                amount,
            } => Light::EnvMap(Box::new(
                sky(*model, *sun, *up, amount, &l.spectrum, r).map_err(e)?,
            )),
            LightKind::Environment { amount } => {
                let (per, g) = emit(amount, None).map_err(e)?;
                Light::Environment(EnvironmentLight {
                    radiance: scaled(&l.spectrum, per, g, r).map_err(e)?,
                })
            }
            LightKind::EnvMap {
                path,
                transform,
                amount,
            } => Light::EnvMap(Box::new(
                envmap(path, transform, amount, &l.spectrum, r).map_err(e)?,
            )),
        };
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
            }));
            weights.push(em.sampling_weight);
        }
        surfaces.push(surface(s.material, s.two_sided, light));
    }
    Ok((lights, weights, surfaces))
}
