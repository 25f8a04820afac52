//! `type = "environment"`: light from every direction at infinity, either constant (a
//! spectrum times radiance, luminance or a scale) or an environment map (`image`, linear sRGB
//! under D65, turned by `transform`, its brightness as mean radiance or luminance over the
//! sphere, irradiance on a plane facing its zenith, or a scale).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "environment",
    what: "an environment light",
    keys: None,
    default_spectrum: flat,
    read,
};

fn read(l: &Lt<'_>) -> R<(LightKind, Spectrum)> {
    let (cx, raw) = (l.cx, l.l);
    let Some(image) = &raw.image else {
        l.only(
            "an environment light",
            &["kind", "spectrum", "radiance", "luminance", "scale"],
        )?;
        let amount = emit_amount(
            cx,
            &l.sp,
            &l.f,
            &raw.radiance,
            &raw.luminance,
            &None,
            &raw.scale,
        )?;
        return Ok((LightKind::Environment { amount }, l.spectrum.clone()));
    };
    l.only(
        "an environment map (an environment light with an image)",
        &[
            "kind",
            "image",
            "transform",
            "radiance",
            "luminance",
            "irradiance",
            "scale",
        ],
    )?;
    let path = cx.path(image.get_ref());
    if !path.is_file() {
        return Err(cx.err(
            &image.span(),
            l.field("image"),
            format!("image file not found: {}", path.display()),
        ));
    }
    let kind = LightKind::EnvMap {
        path,
        transform: match &raw.transform {
            Some(t) => shapes::transform(cx, t, &l.field("transform"))?,
            None => Vec::new(),
        },
        amount: envmap_amount(l)?,
    };
    // the map's pixels are linear sRGB under D65: RGB (1, 1, 1) is D65 of luminance 1 cd/m²
    // before `scale` (or the luminance or radiance that replaces it)
    let spectrum = Spectrum::Piecewise(std::sync::Arc::new(
        crate::spectrum::rgb2spec::d65_unit_luminance()
            .scaled((1.0 / crate::colour::cie::K_M) as f32),
    ));
    Ok((kind, spectrum))
}

/// An environment map's brightness: exactly one of `scale`, `radiance` or `luminance` (means
/// over the sphere), `irradiance` (W/m² or lx on a plane facing the map's zenith).
fn envmap_amount(l: &Lt<'_>) -> R<EnvMapAmount> {
    let (cx, raw) = (l.cx, l.l);
    let (which, v) = one_amount(
        cx,
        &l.sp,
        &l.f,
        &[
            ("scale", &raw.scale),
            ("radiance", &raw.radiance),
            ("luminance", &raw.luminance),
            ("irradiance", &raw.irradiance),
        ],
    )?;
    let field = l.field(which);
    let (amount, si) = match which {
        "radiance" => {
            let r: Radiance = cx.quantity(v, &field)?;
            let x = r.get::<radiance::watt_per_square_meter_steradian>();
            (EnvMapAmount::Radiance(r), x)
        }
        "luminance" => {
            let q: Luminance = cx.quantity(v, &field)?;
            let x = q.get::<luminance::candela_per_square_meter>();
            (EnvMapAmount::Luminance(q), x)
        }
        "irradiance" => match cx.quantity_of(v, &field, &[D::Irradiance, D::Illuminance])? {
            (D::Irradiance, e) => (
                EnvMapAmount::Irradiance(Irradiance::new::<irradiance::watt_per_square_meter>(e)),
                e,
            ),
            (_, lx) => (
                EnvMapAmount::Illuminance(Illuminance::new::<illuminance::lux>(lx)),
                lx,
            ),
        },
        _ => {
            let k = cx.number(v, &field)?;
            (EnvMapAmount::Scale(k), k)
        }
    };
    non_negative(cx, v, &field, si)?;
    Ok(amount)
}
