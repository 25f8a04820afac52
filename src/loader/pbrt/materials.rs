//! pbrt-v4's materials (`src/pbrt/materials.cpp`), each reading its own parameters (pbrt-v4's
//! names and defaults) into the scene description.

use std::path::Path;

use super::lexer::Token;
use super::params::{Params, R};
use super::roughness::{rough, roughness, textured};
use super::{Reader, spectra};
use crate::loader::desc::*;
use crate::loader::{LoadError, Loc};
use crate::spectrum::Spectrum;

/// The named materials defined so far (pbrt-v4 creates them in order, so a `mix` names
/// earlier ones).
pub(super) struct Named<'a> {
    pub index: &'a std::collections::HashMap<String, usize>,
    pub materials: &'a [MaterialDesc],
    /// The named spectrum and float textures defined so far.
    pub textures: &'a std::collections::HashMap<String, TextureDesc>,
    pub float_textures: &'a std::collections::HashMap<String, TextureDesc>,
    /// The folder file names are relative to (pbrt-v4: the first file's).
    pub base: &'a Path,
}

impl Named<'_> {
    /// `name` relative to the scene's folder, unless absolute.
    fn resolve(&self, name: &str) -> std::path::PathBuf {
        self.base.join(name)
    }
}

impl Named<'_> {
    /// A reflectance that may be a named texture (`"texture <name>" "<texture>"`).
    pub(super) fn reflectance(&self, p: &Params, name: &str, default: f64) -> R<TextureDesc> {
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

    /// A float that may be a named float texture; None when absent.
    pub(super) fn float(&self, p: &Params, name: &str) -> R<Option<TextureDesc>> {
        match p.get(name) {
            None => Ok(None),
            Some(q) if q.ty == "texture" => {
                let t = q.strs.first().cloned().unwrap_or_default();
                self.float_textures
                    .get(&t)
                    .cloned()
                    .map(Some)
                    .ok_or_else(|| {
                        p.err(q.loc, format!("\"{name}\": no float texture named \"{t}\""))
                    })
            }
            Some(_) => Ok(Some(Spectrum::Constant(p.float(name, 0.0)? as f32).into())),
        }
    }
}

/// A `Material` or `MakeNamedMaterial` of `kind`.
/// A `thindielectric`: its `eta` a number (a spectral one is refused).
fn thin_dielectric(p: &Params) -> R<MaterialKind> {
    let eta = match spectra::ior(p, "eta", 1.5)? {
        crate::spectrum::ior::Ior::Constant(e) => e as f64,
        _ => {
            return Err(p.err(
                p.loc_of("eta"),
                "a thindielectric's spectral \"eta\" is not read yet (give a float)",
            ));
        }
    };
    Ok(MaterialKind::ThinDielectric {
        int_ior: eta,
        exterior_ior: 1.0,
    })
}

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
        "thindielectric" => thin_dielectric(p)?,
        // pbrt-v4 picks the second material with probability `amount` per hit, whose
        // expectation is the blend (1 − amount)·f₀ + amount·f₁
        "mix" => mix(p, &named)?,
        "diffuse" => MaterialKind::Diffuse {
            reflectance: named.reflectance(p, "reflectance", 0.5)?,
        },
        "dielectric" => {
            let rough = rough(&named, p, "")?;
            textured(
                MaterialKind::Dielectric {
                    ior: spectra::ior(p, "eta", 1.5)?,
                    exterior_ior: 1.0,
                    roughness: rough.fixed(),
                    distribution: crate::material::microfacet::Distribution::Ggx,
                    smith: Smith::HeightCorrelated,
                },
                rough,
            )
        }
        "conductor" => {
            let rough = rough(&named, p, "")?;
            let roughness = rough.fixed();
            let ior = match spectra::conductor(p, "")? {
                Some(ior) => ior,
                None => {
                    spectra::conductor_of_reflectance(&spectra::reflectance(p, "reflectance", 0.0)?)
                }
            };
            textured(
                MaterialKind::Conductor {
                    ior,
                    exterior_ior: 1.0,
                    roughness,
                    distribution: crate::material::microfacet::Distribution::Ggx,
                    smith: Smith::HeightCorrelated,
                },
                rough,
            )
        }
        "diffusetransmission" => {
            let scale = p.float("scale", 1.0)?;
            let scaled = |name: &str| -> R<TextureDesc> {
                Ok(match named.reflectance(p, name, 0.25)? {
                    TextureDesc::Uniform(s) => TextureDesc::Uniform(s.scaled(scale as f32)),
                    t if scale == 1.0 => t,
                    t => {
                        TextureDesc::Scaled(Box::new([t, Spectrum::Constant(scale as f32).into()]))
                    }
                })
            };
            MaterialKind::DiffuseTransmission {
                reflectance: scaled("reflectance")?,
                transmittance: scaled("transmittance")?,
            }
        }
        "coateddiffuse" => {
            let r = rough(&named, p, "")?;
            MaterialKind::Layered(Box::new(LayeredDesc {
                conductor: None,
                reflectance: named.reflectance(p, "reflectance", 0.5)?,
                roughness: r.fixed(),
                roughness_texture: r.texture(),
                eta: spectra::ior(p, "eta", 1.5)?,
                ..slab(p)?
            }))
        }
        "coatedconductor" => {
            let r = rough(&named, p, "interface.")?;
            MaterialKind::Layered(Box::new(LayeredDesc {
                conductor: Some((
                    spectra::conductor(p, "conductor.")?,
                    roughness(p, "conductor.")?,
                )),
                reflectance: spectra::reflectance(p, "reflectance", 0.0)?.into(),
                roughness: r.fixed(),
                roughness_texture: r.texture(),
                eta: spectra::ior(p, "interface.eta", 1.5)?,
                ..slab(p)?
            }))
        }
        "hair" => super::hair::hair(p)?,
        "measured" => measured(p, &named, loc)?,
        other => {
            return Err(p.err(
                loc,
                format!("the material \"{other}\" is not read yet (spectrace reads diffuse, diffusetransmission, dielectric, thindielectric, conductor, coateddiffuse, coatedconductor, hair, measured, mix and interface)"),
            ));
        }
    };
    let kind = perturbed(kind, p, &named)?;
    Ok(MaterialDesc {
        name: name.to_string(),
        kind,
        loc,
    })
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
        roughness_texture: None,
        thickness: p.float("thickness", 0.01)?,
        albedo: spectra::reflectance(p, "albedo", 0.0)?.into(),
        g: p.float("g", 0.0)?,
        max_depth: count("maxdepth", 10)?,
        n_samples,
        pbrt_exit_weight: false,
    })
}

impl Reader {
    /// `MakeNamedMaterial "name" "string type" …`, `Material "type" …` and
    /// `NamedMaterial "name"`.
    pub(super) fn material_directive(
        &mut self,
        d: &str,
        toks: &[Token],
        i: &mut usize,
        file: &Path,
        loc: Loc,
    ) -> R<()> {
        let err = |m: String| LoadError::new(file, loc, "", m);
        let name = Self::string_arg(toks, i, file, d, loc)?;
        if d == "NamedMaterial" {
            return match self.named_materials.get(&name) {
                Some(&m) => {
                    self.state.material = Some(m);
                    Ok(())
                }
                None => Err(err(format!("no material named \"{name}\""))),
            };
        }
        let p = Params::parse(toks, i, file)?.with_defaults(&self.state.attributes.material);
        let kind = if d == "Material" {
            name.clone()
        } else {
            p.string("type")?.ok_or_else(|| {
                err(format!(
                    "MakeNamedMaterial \"{name}\" needs a \"string type\""
                ))
            })?
        };
        let m = material(&kind, &p, loc, &name, self.named())?;
        p.check_unused(&format!("material \"{kind}\""))?;
        self.materials.push(m);
        if d == "Material" {
            self.state.material = Some(self.materials.len() - 1);
        } else {
            self.named_materials.insert(name, self.materials.len() - 1);
        }
        Ok(())
    }
}

/// pbrt-v4's `measured`: the RGL `.bsdf` file `filename` (relative to the scene's directory).
fn measured(p: &Params, named: &Named<'_>, loc: Loc) -> R<MaterialKind> {
    let Some(file) = p.string("filename")? else {
        return Err(p.err(
            loc,
            "a measured material needs \"string filename\" (an RGL .bsdf file)",
        ));
    };
    let path = named.resolve(&file);
    let table = crate::loader::mitsuba::rgl::read_rgl_bsdf(&path)
        .map_err(|e| p.err(p.loc_of("filename"), e))?;
    // pbrt-v4 multiplies by D/(4σ) whatever the file's `jacobian` flag says
    Ok(MaterialKind::Measured {
        table: std::sync::Arc::new(table),
        jacobian: true,
    })
}

/// pbrt-v4's `mix`: two named materials defined before it, blended by `amount` (0.5), a
/// number or a float texture (grey, as the blend's weight must be).
fn mix(p: &Params, named: &Named<'_>) -> R<MaterialKind> {
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
    // a number, or a float texture (grey, as the blend's weight must be)
    let weight = match named.float(p, "amount")? {
        None => Spectrum::Constant(0.5).into(),
        Some(TextureDesc::Uniform(Spectrum::Constant(a))) => {
            Spectrum::Constant(a.clamp(0.0, 1.0)).into()
        }
        Some(t) => t,
    };
    Ok(MaterialKind::Blend {
        weight,
        a: Box::new(kinds[0].clone()),
        b: Box::new(kinds[1].clone()),
    })
}

/// `kind` under its `displacement` or `normalmap`, if it has one.
fn perturbed(kind: MaterialKind, p: &Params, named: &Named<'_>) -> R<MaterialKind> {
    // pbrt-v4's `displacement`: a float texture of heights along the shading normal, bump
    // mapped as pbrt-v4 does (by the texture's gradient, not pbrt-v4's finite differences);
    // else its `normalmap`, an image read linearly at (u, 1 − v), repeated, bilinear
    let displacement = named.float(p, "displacement")?;
    if displacement
        .as_ref()
        .is_some_and(TextureDesc::reads_position)
    {
        return Err(p.err(
            p.loc_of("displacement"),
            "a displacement texture of a spherical, cylindrical or planar mapping is not read yet (spectrace reads uv there)",
        ));
    }
    let normal_map = p.string("normalmap")?;
    Ok(match (displacement, normal_map) {
        _ if matches!(kind, MaterialKind::Null) => kind,
        (Some(height), _) => MaterialKind::BumpMap {
            height,
            scale: 1.0,
            inner: Box::new(kind),
            pbrt: true,
        },
        (None, Some(file)) => {
            let path = named.resolve(&file);
            if !path.is_file() {
                return Err(p.err(
                    p.loc_of("normalmap"),
                    format!("no image \"{}\"", path.display()),
                ));
            }
            let flip_v = vec![TransformStep::Matrix([
                1.0, 0.0, 0.0, 0.0, //
                0.0, -1.0, 0.0, 1.0, //
                0.0, 0.0, 1.0, 0.0, //
                0.0, 0.0, 0.0, 1.0,
            ])];
            MaterialKind::NormalMap {
                map: TextureDesc::Bitmap {
                    path,
                    filter: crate::texture::TexFilter::Bilinear,
                    wrap: crate::texture::Wrap::Repeat,
                    raw: true,
                    to_uv: flip_v,
                    loc: p.loc_of("normalmap"),
                },
                inner: Box::new(kind),
                pbrt: true,
            }
        }
        (None, None) => kind,
    })
}
