//! The pbrt-v4 kinds spectrace reads: each reads its own parameters (pbrt-v4's names and
//! defaults, `src/pbrt/shapes.cpp`, `materials.cpp`, `lights.cpp`, `cameras.cpp`, `film.cpp`)
//! into the scene description. Lengths are read as metres (pbrt's files have no unit).

use std::f64::consts::PI;

use glam::{DMat4, DVec3};

use super::params::{Params, R};
use super::shapes::len;
use super::{Reader, spectra};
use crate::loader::desc::*;
use crate::loader::{LoadError, Loc};
use crate::spectrum::Spectrum;
use crate::units::{Angle, Length, angle::degree};

/// An `AreaLightSource "diffuse"`: its emitted radiance (W·m⁻²·sr⁻¹·nm⁻¹ per unit of pbrt's
/// spectrum, see [`spectra::illuminant`]) and whether both sides emit.
#[derive(Clone, Debug)]
pub(super) struct AreaLight {
    pub spectrum: Spectrum,
    pub scale: f64,
    pub two_sided: bool,
    /// pbrt-v4's `power` (∫ȳ·Φ dλ of each shape, each triangle of a mesh), if given.
    pub power: Option<f64>,
    pub loc: Loc,
}

/// The named materials defined so far (pbrt-v4 creates them in order, so a `mix` names
/// earlier ones).
pub(super) struct Named<'a> {
    pub index: &'a std::collections::HashMap<String, usize>,
    pub materials: &'a [MaterialDesc],
    /// The named spectrum textures defined so far.
    pub textures: &'a std::collections::HashMap<String, TextureDesc>,
}

impl Named<'_> {
    /// A reflectance that may be a named texture (`"texture <name>" "<texture>"`).
    fn reflectance(&self, p: &Params, name: &str, default: f64) -> R<TextureDesc> {
        match p.get(name) {
            Some(q) if q.ty == "texture" => {
                let t = q.strs.first().cloned().unwrap_or_default();
                self.textures.get(&t).cloned().ok_or_else(|| {
                    p.err(
                        q.loc,
                        format!("\"{name}\": no spectrum texture named \"{t}\""),
                    )
                })
            }
            _ => Ok(spectra::reflectance(p, name, default)?.into()),
        }
    }
}

/// A `Material` or `MakeNamedMaterial` of `kind`.
pub(super) fn material(
    kind: &str,
    p: &Params,
    loc: Loc,
    name: &str,
    named: Named<'_>,
) -> R<MaterialDesc> {
    let kind = match kind {
        // a surface that only bounds media: light passes straight through (media are not read
        // yet; spectrace counts the crossing as a scattering event, pbrt-v4 does not)
        "interface" | "" | "none" => MaterialKind::Null,
        "thindielectric" => {
            let eta = match spectra::ior(p, "eta", 1.5)? {
                crate::spectrum::ior::Ior::Constant(e) => e as f64,
                _ => {
                    return Err(p.err(
                        p.loc_of("eta"),
                        "a thindielectric's spectral \"eta\" is not read yet (give a float)",
                    ));
                }
            };
            MaterialKind::ThinDielectric {
                int_ior: eta,
                exterior_ior: 1.0,
            }
        }
        // pbrt-v4 picks the second material with probability `amount` per hit, whose
        // expectation is the blend (1 − amount)·f₀ + amount·f₁
        "mix" => {
            let names = match p.get("materials") {
                Some(q) if q.ty == "string" && q.strs.len() == 2 => q.strs.clone(),
                _ => {
                    return Err(p.err(
                        p.loc_of("materials"),
                        "a mix needs \"string materials\" with two names",
                    ));
                }
            };
            let mut kinds = Vec::new();
            for n in &names {
                let Some(&i) = named.index.get(n) else {
                    return Err(p.err(
                        p.loc_of("materials"),
                        format!("no material named \"{n}\" defined before the mix"),
                    ));
                };
                kinds.push(named.materials[i].kind.clone());
            }
            let amount = p.float("amount", 0.5)?;
            MaterialKind::Blend {
                weight: Spectrum::Constant(amount.clamp(0.0, 1.0) as f32).into(),
                a: Box::new(kinds[0].clone()),
                b: Box::new(kinds[1].clone()),
            }
        }
        "diffuse" => MaterialKind::Diffuse {
            reflectance: named.reflectance(p, "reflectance", 0.5)?,
        },
        "dielectric" => {
            let roughness = roughness(p, "")?;
            MaterialKind::Dielectric {
                ior: spectra::ior(p, "eta", 1.5)?,
                exterior_ior: 1.0,
                roughness,
                distribution: crate::material::microfacet::Distribution::Ggx,
                smith: Smith::HeightCorrelated,
            }
        }
        "conductor" => {
            let roughness = roughness(p, "")?;
            let ior = match spectra::conductor(p, "")? {
                Some(ior) => ior,
                None => {
                    spectra::conductor_of_reflectance(&spectra::reflectance(p, "reflectance", 0.0)?)
                }
            };
            MaterialKind::Conductor {
                ior,
                exterior_ior: 1.0,
                roughness,
                distribution: crate::material::microfacet::Distribution::Ggx,
                smith: Smith::HeightCorrelated,
            }
        }
        "coateddiffuse" => MaterialKind::Layered(Box::new(LayeredDesc {
            conductor: None,
            reflectance: named.reflectance(p, "reflectance", 0.5)?,
            roughness: roughness(p, "")?,
            eta: spectra::ior(p, "eta", 1.5)?,
            ..slab(p)?
        })),
        "coatedconductor" => MaterialKind::Layered(Box::new(LayeredDesc {
            conductor: Some((
                spectra::conductor(p, "conductor.")?,
                roughness(p, "conductor.")?,
            )),
            reflectance: spectra::reflectance(p, "reflectance", 0.0)?.into(),
            roughness: roughness(p, "interface.")?,
            eta: spectra::ior(p, "interface.eta", 1.5)?,
            ..slab(p)?
        })),
        other => {
            return Err(p.err(
                loc,
                format!("the material \"{other}\" is not read yet (spectrace reads diffuse, dielectric, thindielectric, conductor, coateddiffuse, coatedconductor, mix and interface)"),
            ));
        }
    };
    Ok(MaterialDesc {
        name: name.to_string(),
        kind,
        loc,
    })
}

/// pbrt-v4's microfacet roughness: `roughness`, or `uroughness`/`vroughness` (0), turned into
/// α by `remaproughness` (true: α = √r, pbrt-v4's `TrowbridgeReitzDistribution::RoughnessToAlpha`);
/// None when smooth (α = 0 in pbrt-v4 is its specular case).
fn roughness(p: &Params, prefix: &str) -> R<Option<[f64; 2]>> {
    let r = p.float(&format!("{prefix}roughness"), 0.0)?;
    let u = p.float(&format!("{prefix}uroughness"), r)?;
    let v = p.float(&format!("{prefix}vroughness"), r)?;
    let remap = p.bool("remaproughness", true)?;
    let alpha = |x: f64| if remap { x.max(0.0).sqrt() } else { x };
    let (au, av) = (alpha(u), alpha(v));
    // pbrt-v4's `EffectivelySmooth`: max(α_x, α_y) < 10⁻³
    Ok((au.max(av) >= 1e-3).then_some([au, av]))
}

/// The slab of a layered material (pbrt-v4's `thickness` 0.01, `albedo` 0, `g` 0, `maxdepth`
/// 10, `nsamples` 1); the base and coating are the caller's.
fn slab(p: &Params) -> R<LayeredDesc> {
    let count = |name: &str, default: i64| -> R<u32> {
        let n = p.int(name, default)?;
        u32::try_from(n).map_err(|_| p.err(p.loc_of(name), format!("\"{name}\" must be ≥ 0")))
    };
    let n_samples = count("nsamples", 1)?;
    if n_samples == 0 {
        return Err(p.err(p.loc_of("nsamples"), "\"nsamples\" must be ≥ 1"));
    }
    Ok(LayeredDesc {
        conductor: None,
        reflectance: Spectrum::Constant(0.0).into(),
        eta: crate::spectrum::ior::Ior::Constant(1.5),
        roughness: None,
        thickness: p.float("thickness", 0.01)?,
        albedo: spectra::reflectance(p, "albedo", 0.0)?.into(),
        g: p.float("g", 0.0)?,
        max_depth: count("maxdepth", 10)?,
        n_samples,
        pbrt_exit_weight: false,
    })
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
                format!("the light \"{other}\" is not read yet (spectrace reads point, spot, distant and infinite)"),
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
            transform: vec![super::shapes::matrix_step(ctm)],
            amount,
        },
        spectrum: Spectrum::Piecewise(crate::spectrum::rgb2spec::d65_unit_luminance()),
        sampling_weight: 1.0,
        loc,
    })
}

/// An `AreaLightSource`.
pub(super) fn area_light(kind: &str, p: &Params, loc: Loc) -> R<AreaLight> {
    if kind != "diffuse" {
        return Err(p.err(
            loc,
            format!("the area light \"{kind}\" is not read (pbrt-v4 has only \"diffuse\")"),
        ));
    }
    if p.get("filename").is_some() {
        return Err(p.err(
            p.loc_of("filename"),
            "an area light's image is not read yet",
        ));
    }
    let (spectrum, k) = spectra::illuminant(p, "L")?;
    let power = p.float("power", -1.0)?;
    Ok(AreaLight {
        spectrum,
        scale: p.float("scale", 1.0)? * k,
        two_sided: p.bool("twosided", false)?,
        power: (power > 0.0).then_some(power),
        loc,
    })
}

/// The samples per pixel a `Sampler` asks for (pbrt-v4's defaults: 16, `independent` 4,
/// `stratified` `xsamples` × `ysamples`, 4 × 4); spectrace samples with its own sequence.
fn sampler_spp(p: &Params, kind: &str) -> R<i64> {
    let n = match kind {
        "zsobol" | "halton" | "sobol" | "paddedsobol" | "pmj02bn" => p.int("pixelsamples", 16)?,
        "independent" => p.int("pixelsamples", 4)?,
        "stratified" => {
            let _ = p.bool("jitter", true)?;
            p.int("xsamples", 4)? * p.int("ysamples", 4)?
        }
        other => {
            return Err(p.err(
                p.loc_of("pixelsamples"),
                format!("unknown sampler \"{other}\""),
            ));
        }
    };
    // read as pbrt-v4 reads them; spectrace's sampler has its own scrambling
    let _ = (p.int("seed", 0)?, p.string("randomization")?);
    p.check_unused(&format!("sampler \"{kind}\""))?;
    Ok(n)
}

/// An `Integrator`: `path` and `volpath` (spectrace's path tracer: media are not read yet),
/// `bdpt`, `lightpath` (spectrace's light tracer); `maxdepth` (5), `lightsampler` (`bvh`,
/// `power`, `uniform`).
fn integrator(p: &Params, kind: &str, loc: Loc) -> R<(IntegratorKind, i64, LightSelection)> {
    let k = match kind {
        "path" | "volpath" => IntegratorKind::Path,
        "bdpt" => IntegratorKind::Bdpt,
        "lightpath" => IntegratorKind::Light,
        other => {
            return Err(p.err(
                loc,
                format!("the integrator \"{other}\" is not read yet (spectrace reads path, volpath, bdpt and lightpath)"),
            ));
        }
    };
    let depth = p.int("maxdepth", 5)?;
    let selection = if matches!(kind, "path" | "volpath") {
        match p.string("lightsampler")?.as_deref().unwrap_or("bvh") {
            "bvh" => LightSelection::Tree,
            "power" => LightSelection::Power,
            "uniform" => LightSelection::Uniform,
            other => {
                return Err(p.err(
                    p.loc_of("lightsampler"),
                    format!("the light sampler \"{other}\" is not read (spectrace reads bvh, power and uniform)"),
                ));
            }
        }
    } else {
        LightSelection::Tree
    };
    if p.bool("regularize", false)? {
        return Err(p.err(p.loc_of("regularize"), "\"regularize\" is not read yet"));
    }
    if kind == "bdpt" {
        for v in ["visualizestrategies", "visualizeweights"] {
            if p.bool(v, false)? {
                return Err(p.err(p.loc_of(v), format!("\"{v}\" is not read")));
            }
        }
    }
    p.check_unused(&format!("integrator \"{kind}\""))?;
    Ok((k, depth, selection))
}

/// The scene: camera, film, sampler and integrator from their directives, and what the world
/// block made.
pub(super) fn finish(r: Reader) -> Result<SceneDesc, LoadError> {
    let file = r.root.clone();
    let Some((ctm, cam, kind, cam_loc)) = &r.camera else {
        return Err(LoadError::new(
            &file,
            Loc { line: 1, col: 1 },
            "",
            "the scene has no Camera",
        ));
    };
    let (width, height, film_loc) = match &r.film {
        Some((p, kind, loc)) => {
            if kind != "rgb" {
                return Err(p.err(
                    *loc,
                    format!("the film \"{kind}\" is not read yet (spectrace reads \"rgb\")"),
                ));
            }
            let w = p.int("xresolution", 1280)?;
            let h = p.int("yresolution", 720)?;
            let _ = p.string("filename")?;
            p.check_unused("film \"rgb\"")?;
            (w, h, *loc)
        }
        None => (1280, 720, Loc { line: 0, col: 0 }),
    };
    if !(1..=32768).contains(&width) || !(1..=32768).contains(&height) {
        return Err(LoadError::new(
            &file,
            film_loc,
            "",
            format!("a film of {width} × {height} pixels"),
        ));
    }
    let spp = match &r.sampler {
        Some((p, kind, _)) => sampler_spp(p, kind)?,
        None => 16,
    };
    let (integrator, max_depth, light_selection) = match &r.integrator {
        Some((p, kind, loc)) => integrator(p, kind, *loc)?,
        // pbrt-v4's default, `volpath`: `path` where there are no media
        None => (IntegratorKind::Path, 5, LightSelection::Tree),
    };
    let camera = camera(ctm, cam, kind, *cam_loc, width, height)?;
    cam.check_unused(&format!("camera \"{kind}\""))?;
    let nm = |x: f64| Length::new::<crate::units::length::nanometer>(x);
    Ok(SceneDesc {
        path: file.clone(),
        wavelength_range: [nm(360.0), nm(830.0)],
        camera,
        film: FilmDesc {
            width: width as u32,
            height: height as u32,
            spp: spp.clamp(1, 1 << 24) as u32,
            // pbrt-v4's default pixel filter: a Gaussian of radius 1.5 px, σ 0.5
            filter: crate::film::filter::gaussian::Desc::pbrt(0.5, 1.5),
            spectral_bins: 0,
            exposure_ev: None,
            loc: film_loc,
        },
        integrator: IntegratorDesc {
            kind: integrator,
            max_depth: max_depth.clamp(0, 1 << 16) as u32,
            rr_depth: 1,
            light_selection,
            moment: false,
            polarised: false,
            split_dispersion: true,
            aovs: Vec::new(),
        },
        materials: r.materials,
        shapes: r.shapes,
        groups: r.groups,
        instances: r.instances,
        lights: r.lights,
        media: Vec::new(),
        camera_medium: None,
        sensors: Vec::new(),
        notes: r.notes,
    })
}

/// A `perspective` camera: pbrt-v4's `fov` spans the image's shorter axis; its camera space
/// has +x to the image's right, so the image is spectrace's mirrored left to right.
fn camera(ctm: &DMat4, p: &Params, kind: &str, loc: Loc, w: i64, h: i64) -> R<CameraDesc> {
    for unread in [
        "lensradius",
        "focaldistance",
        "screenwindow",
        "frameaspectratio",
    ] {
        if p.get(unread).is_some() {
            return Err(p.err(
                p.loc_of(unread),
                format!("a camera's \"{unread}\" is not read yet"),
            ));
        }
    }
    let world_from_camera = ctm.inverse();
    let kind = match kind {
        "perspective" => {
            let fov = p.float("fov", 90.0)?;
            if !(fov > 0.0 && fov < 180.0) {
                return Err(p.err(
                    p.loc_of("fov"),
                    format!("fov must lie in (0, 180) degrees, not {fov}"),
                ));
            }
            CameraKind::Perspective {
                projection: Projection::Fov {
                    fov: Angle::new::<degree>(fov),
                    axis: FovAxis::Smaller,
                },
            }
        }
        // pbrt-v4's default screen window spans [−1, 1] of camera space across the shorter
        // image axis
        "orthographic" => {
            let aspect = w as f64 / h as f64;
            let unit = world_from_camera.transform_vector3(DVec3::X).length();
            CameraKind::Orthographic {
                view_width: len(2.0 * aspect.max(1.0) * unit),
            }
        }
        other => {
            return Err(p.err(
                loc,
                format!("the camera \"{other}\" is not read yet (spectrace reads \"perspective\" and \"orthographic\")"),
            ));
        }
    };
    let eye = world_from_camera.transform_point3(DVec3::ZERO);
    let target = world_from_camera.transform_point3(DVec3::Z);
    let up = world_from_camera.transform_vector3(DVec3::Y);
    Ok(CameraDesc {
        kind,
        eye: [len(eye.x), len(eye.y), len(eye.z)],
        target: [len(target.x), len(target.y), len(target.z)],
        up: up.to_array(),
        mirror: true,
        sensor: None,
        loc,
    })
}
