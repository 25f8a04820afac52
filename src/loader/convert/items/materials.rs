//! `[materials.NAME]`, with the energy check on reflectances.

use super::*;

/// Checks 0 ≤ S(λ) ≤ 1 over the simulated range and the CIE range at 1 nm.
pub(super) fn check_reflectance(
    cx: &Cx<'_>,
    s: &Spectrum,
    span: &Range<usize>,
    field: &str,
    range: &[Length; 2],
) -> R<()> {
    let lo = range[0].get::<length::nanometer>().min(360.0) as i64;
    let hi = range[1].get::<length::nanometer>().max(830.0) as i64;
    for l in lo..=hi {
        let v = s.eval(l as f32);
        if !(0.0..=1.0 + 1e-6).contains(&v) {
            return Err(cx.err(
                span,
                field,
                format!("reflectance is {v} at {l} nm; it must lie in [0, 1], or the surface would create energy"),
            ));
        }
    }
    Ok(())
}

pub(super) fn material(
    cx: &Cx<'_>,
    name: &S<String>,
    m: &S<RawMaterial>,
    range: &[Length; 2],
) -> R<MaterialDesc> {
    let sp = m.span();
    let f = format!("materials.{}", name.get_ref());
    let m = m.get_ref();
    let all = present!(m; kind, reflectance, kd, ks, exponent, ior, exterior_ior, metal, eta, k, roughness);
    let ty = cx.required(
        &m.kind,
        &sp,
        &format!("{f}.type"),
        "diffuse, phong, dielectric or conductor",
    )?;
    let roughness = |cx: &Cx<'_>| -> R<Option<f64>> {
        match &m.roughness {
            None => Ok(None),
            Some(r) => {
                let a = cx.number(r, &format!("{f}.roughness"))?;
                if !(0.0..=1.0).contains(&a) {
                    return Err(cx.err(
                        &r.span(),
                        format!("{f}.roughness"),
                        format!("expected a GGX α in [0, 1], found {a}"),
                    ));
                }
                Ok((a > 0.0).then_some(a))
            }
        }
    };
    let exterior = |cx: &Cx<'_>| -> R<f64> {
        match &m.exterior_ior {
            None => Ok(1.0),
            Some(e) => {
                let n = cx.number(e, &format!("{f}.exterior_ior"))?;
                if n < 1.0 {
                    return Err(cx.err(
                        &e.span(),
                        format!("{f}.exterior_ior"),
                        format!("expected an index ≥ 1, found {n}"),
                    ));
                }
                Ok(n)
            }
        }
    };
    let kind = match ty.get_ref().as_str() {
        "diffuse" => {
            cx.only("a diffuse material", &f, &all, &["kind", "reflectance"])?;
            let r = cx.required(
                &m.reflectance,
                &sp,
                &format!("{f}.reflectance"),
                "a reflectance spectrum",
            )?;
            let reflectance =
                cx.spectrum(r, &format!("{f}.reflectance"), SpectrumUse::Reflectance)?;
            check_reflectance(
                cx,
                &reflectance,
                &r.span(),
                &format!("{f}.reflectance"),
                range,
            )?;
            MaterialKind::Diffuse { reflectance }
        }
        "phong" => {
            cx.only(
                "a phong material",
                &f,
                &all,
                &["kind", "kd", "ks", "exponent"],
            )?;
            let kd_v = cx.required(
                &m.kd,
                &sp,
                &format!("{f}.kd"),
                "a diffuse reflectance spectrum",
            )?;
            let ks_v = cx.required(
                &m.ks,
                &sp,
                &format!("{f}.ks"),
                "a specular reflectance spectrum",
            )?;
            let kd = cx.spectrum(kd_v, &format!("{f}.kd"), SpectrumUse::Reflectance)?;
            let ks = cx.spectrum(ks_v, &format!("{f}.ks"), SpectrumUse::Reflectance)?;
            let sum = SumCheck(&kd, &ks);
            check_reflectance(
                cx,
                &sum.spectrum(),
                &ks_v.span(),
                &format!("{f}.kd + {f}.ks"),
                range,
            )?;
            let e = cx.required(
                &m.exponent,
                &sp,
                &format!("{f}.exponent"),
                "a shininess exponent ≥ 0",
            )?;
            let exponent = cx.number(e, &format!("{f}.exponent"))?;
            if !(0.0..=1e6).contains(&exponent) {
                return Err(cx.err(
                    &e.span(),
                    format!("{f}.exponent"),
                    format!("expected 0 to 1e6, found {exponent}"),
                ));
            }
            MaterialKind::Phong { kd, ks, exponent }
        }
        "dielectric" => {
            cx.only(
                "a dielectric material",
                &f,
                &all,
                &["kind", "ior", "exterior_ior", "roughness"],
            )?;
            let i = cx.required(
                &m.ior,
                &sp,
                &format!("{f}.ior"),
                "an index: a number or a glass name like \"N-BK7\"",
            )?;
            MaterialKind::Dielectric {
                ior: cx.ior(i, &format!("{f}.ior"))?,
                exterior_ior: exterior(cx)?,
                roughness: roughness(cx)?,
                distribution: Distribution::Ggx,
            }
        }
        "conductor" => {
            cx.only(
                "a conductor material",
                &f,
                &all,
                &["kind", "metal", "eta", "k", "exterior_ior", "roughness"],
            )?;
            let ior = match (&m.metal, &m.eta, &m.k) {
                (Some(mm), None, None) => cx.metal(mm, &format!("{f}.metal"))?,
                (None, Some(e), Some(k)) => cx.eta_k(e, k, &f)?,
                _ => {
                    return Err(cx.err(
                        &sp,
                        &f,
                        "a conductor needs either `metal` (e.g. \"Au\") or both `eta` and `k`",
                    ));
                }
            };
            MaterialKind::Conductor {
                ior,
                exterior_ior: exterior(cx)?,
                roughness: roughness(cx)?,
                distribution: Distribution::Ggx,
            }
        }
        o => {
            return Err(cx.err(&ty.span(), format!("{f}.type"), format!("unknown material type \"{o}\"; expected diffuse, phong, dielectric or conductor")));
        }
    };
    Ok(MaterialDesc {
        name: name.get_ref().clone(),
        kind,
        loc: cx.src.span(&sp),
    })
}

/// kd + ks as one spectrum, for the energy check.
struct SumCheck<'a>(&'a Spectrum, &'a Spectrum);
impl SumCheck<'_> {
    fn spectrum(&self) -> Spectrum {
        // tabulate at 1 nm over a wide range; only used for the check
        let l: Vec<f32> = (200..=2000).map(|x| x as f32).collect();
        let v: Vec<f32> = l.iter().map(|&x| self.0.eval(x) + self.1.eval(x)).collect();
        match crate::spectrum::PiecewiseLinear::new(l, v) {
            Ok(t) => Spectrum::Piecewise(std::sync::Arc::new(t)),
            Err(_) => Spectrum::Constant(f32::NAN),
        }
    }
}
