//! `[integrator]`.

use super::*;

pub(super) fn integrator(cx: &Cx<'_>, i: Option<&S<RawIntegrator>>) -> R<IntegratorDesc> {
    let mut d = IntegratorDesc {
        kind: IntegratorKind::Path,
        max_depth: 16,
        rr_depth: DEFAULT_RR_DEPTH,
        light_selection: LightSelection::Tree,
        moment: false,
        polarised: false,
        split_dispersion: true,
        aovs: Vec::new(),
        skip_null: false,
    };
    let Some(i) = i else { return Ok(d) };
    let i = i.get_ref();
    if let Some(k) = &i.kind {
        let name = k.get_ref().as_str();
        d.kind = match IntegratorKind::from_name(name) {
            // `direct` takes its sample counts (default 1 each, Mitsuba's)
            Some(IntegratorKind::Direct { .. }) => IntegratorKind::Direct {
                emitter_samples: match &i.emitter_samples {
                    Some(v) => cx.int(v, "integrator.emitter_samples", 0, 1 << 16)? as u32,
                    None => 1,
                },
                bsdf_samples: match &i.bsdf_samples {
                    Some(v) => cx.int(v, "integrator.bsdf_samples", 0, 1 << 16)? as u32,
                    None => 1,
                },
            },
            Some(kind) => kind,
            None => {
                return Err(cx.err(
                    &k.span(),
                    "integrator.type",
                    format!(
                        "\"{name}\"{}: expected {}",
                        crate::params::did_you_mean(name, IntegratorKind::NAMES.into_iter()),
                        IntegratorKind::NAMES.join(", ")
                    ),
                ));
            }
        };
        if let IntegratorKind::Direct {
            emitter_samples: 0,
            bsdf_samples: 0,
        } = d.kind
        {
            return Err(cx.err(
                &k.span(),
                "integrator",
                "direct needs at least one emitter or BSDF sample",
            ));
        }
    }
    for (key, v) in [
        ("emitter_samples", &i.emitter_samples),
        ("bsdf_samples", &i.bsdf_samples),
    ] {
        if let Some(v) = v
            && !matches!(d.kind, IntegratorKind::Direct { .. })
        {
            return Err(cx.err(
                &v.span(),
                format!("integrator.{key}"),
                "applies to type = \"direct\" only",
            ));
        }
    }
    d.moment = i.second_moment.as_ref().is_some_and(|b| *b.get_ref());
    d.polarised = i.polarised.as_ref().is_some_and(|b| *b.get_ref());
    if let Some(m) = &i.max_depth {
        d.max_depth = cx.int(m, "integrator.max_depth", 1, 1024)? as u32;
    }
    if let Some(r) = &i.rr_depth {
        d.rr_depth = cx.int(r, "integrator.rr_depth", 1, 1024)? as u32;
    }
    if let Some(k) = &i.light_selection {
        d.light_selection = match k.get_ref().as_str() {
            "tree" => LightSelection::Tree,
            "power" => LightSelection::Power,
            "uniform" => LightSelection::Uniform,
            o => {
                return Err(cx.err(
                    &k.span(),
                    "integrator.light_selection",
                    format!("\"{o}\": expected tree, power or uniform"),
                ));
            }
        };
    }
    if let Some(k) = &i.dispersion {
        d.split_dispersion = match k.get_ref().as_str() {
            "split" => true,
            "hero" => false,
            o => {
                return Err(cx.err(
                    &k.span(),
                    "integrator.dispersion",
                    format!("\"{o}\": expected split or hero"),
                ));
            }
        };
    }
    Ok(d)
}
