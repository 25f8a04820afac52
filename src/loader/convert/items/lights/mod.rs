//! `[[lights]]`: dispatch by `type` through [`KINDS`], one reader per kind in its own file
//! (the sun's placement and skies in `daylight.rs`, luminaires in `luminaire.rs`).
//!
//! A kind's file holds its `Kind`: its `type` name, the keys it takes and a reader from an
//! [`Lt`] (the light's keys, with located errors and the readers lights share: position, aim,
//! the spectrum and a point-like light's amount). Keys the kind does not take are errors naming
//! them and the keys it takes.

mod beam;
mod daylight;
mod directional;
mod environment;
mod luminaire;
mod point;
mod spot;

use super::*;

/// A light kind's TOML reader.
pub(super) struct Kind {
    /// The `type` name.
    name: &'static str,
    /// "a point light", for messages.
    what: &'static str,
    /// The keys it takes besides `type` (None: the reader checks them, as they depend on
    /// which are given).
    keys: Option<&'static [&'static str]>,
    /// The emission's shape when `spectrum` is not given.
    default_spectrum: fn() -> Spectrum,
    /// Reads the light and its emission spectrum; the keys were checked against `keys`.
    read: fn(&Lt<'_>) -> R<(LightKind, Spectrum)>,
}

/// A flat spectrum, most lights' default shape.
fn flat() -> Spectrum {
    Spectrum::Constant(1.0)
}

/// Every light kind of the TOML format, in the order "expected …" lists them.
const KINDS: &[Kind] = &[
    point::KIND,
    spot::KIND,
    directional::DIRECTIONAL,
    directional::SUN,
    environment::KIND,
    daylight::SKY,
    beam::KIND,
    luminaire::KIND,
];

/// One light being read: its keys and where it stands.
pub(super) struct Lt<'a> {
    cx: &'a Cx<'a>,
    /// `lights[i]`, the prefix of every field in errors.
    f: String,
    /// The light's table.
    sp: Range<usize>,
    l: &'a RawLight,
    /// The keys present, with their spans.
    present: Vec<(&'static str, Range<usize>)>,
    /// `spectrum`, the emission's shape, or the kind's default.
    spectrum: Spectrum,
}

impl Lt<'_> {
    /// `lights[i].key`.
    fn field(&self, key: &str) -> String {
        format!("{}.{key}", self.f)
    }

    /// The value in `v` (one of `l`'s keys, named `key`), or an error saying it is missing and
    /// `what` it should be.
    fn required<'v, T>(&self, v: &'v Option<S<T>>, key: &str, what: &str) -> R<&'v S<T>> {
        self.cx.required(v, &self.sp, &self.field(key), what)
    }

    /// Rejects keys that do not apply to a light that is `what` (used by kinds whose keys
    /// depend on which of them are given).
    fn only(&self, what: &str, allowed: &[&str]) -> R<()> {
        self.cx.only(what, &self.f, &self.present, allowed)
    }

    fn position(&self) -> R<Point> {
        let p = self.required(&self.l.position, "position", "a position [x, y, z]")?;
        self.cx.point(p, &self.field("position"))
    }

    /// `position` and a distinct `target`, for lights that aim; `what` names what aims.
    fn aim(&self, what: &str) -> R<(Point, Point)> {
        let position = self.position()?;
        let t = self.required(
            &self.l.target,
            "target",
            &format!("the point the {what} aims at"),
        )?;
        let target = self.cx.point(t, &self.field("target"))?;
        if (0..3).all(|k| target[k] == position[k]) {
            return Err(self.cx.err(
                &t.span(),
                self.field("target"),
                "the target equals the position",
            ));
        }
        Ok((position, target))
    }

    /// A point-like light's amount: exactly one of `power` (W or lm), `intensity` (W/sr or
    /// cd) or `scale`, never negative.
    fn point_amount(&self) -> R<PointAmount> {
        let (cx, l) = (self.cx, self.l);
        let (which, v) = one_amount(
            cx,
            &self.sp,
            &self.f,
            &[
                ("power", &l.power),
                ("intensity", &l.intensity),
                ("scale", &l.scale),
            ],
        )?;
        let field = self.field(which);
        let (amount, si) = match which {
            "power" => match cx.quantity_of(v, &field, &[D::Power, D::LuminousFlux])? {
                (D::Power, w) => (PointAmount::Power(Power::new::<power::watt>(w)), w),
                (_, lm) => (
                    PointAmount::LuminousFlux(LuminousFlux::new::<luminous_flux::lumen>(lm)),
                    lm,
                ),
            },
            "intensity" => {
                match cx.quantity_of(v, &field, &[D::RadiantIntensity, D::LuminousIntensity])? {
                    (D::RadiantIntensity, w) => (
                        PointAmount::Intensity(RadiantIntensity::new::<
                            radiant_intensity::watt_per_steradian,
                        >(w)),
                        w,
                    ),
                    (_, cd) => (
                        PointAmount::LuminousIntensity(LuminousIntensity::new::<
                            luminous_intensity::candela,
                        >(cd)),
                        cd,
                    ),
                }
            }
            _ => {
                let s = cx.number(v, &field)?;
                (PointAmount::Scale(s), s)
            }
        };
        non_negative(cx, v, &field, si)?;
        Ok(amount)
    }
}

pub(super) fn light(cx: &Cx<'_>, i: usize, l: &S<RawLight>) -> R<LightDesc> {
    let sp = l.span();
    let f = format!("lights[{i}]");
    let l = l.get_ref();
    let present = present!(l; kind, spectrum, position, target, direction, power, intensity, radiance, luminance, irradiance, scale, cone_angle, falloff_start, falloff, angular_diameter, radius, image, transform, file, c0, tilt, model, sun_elevation, sun_azimuth, latitude, longitude, time, up, north);
    let names: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
    let field = format!("{f}.type");
    let ty = cx.required(&l.kind, &sp, &field, &names.join(", "))?;
    // the spectrum first (before the keys and the type are checked), in its kind's default
    let default = KINDS
        .iter()
        .find(|k| k.name == ty.get_ref())
        .map_or(flat as fn() -> Spectrum, |k| k.default_spectrum);
    let spectrum = match &l.spectrum {
        Some(s) => cx.spectrum(s, &format!("{f}.spectrum"), SpectrumUse::Emission)?,
        None => default(),
    };
    let kind = &KINDS[cx.kind_index(ty.get_ref(), &ty.span(), &field, "light", &names)?];
    if let Some(keys) = kind.keys {
        let mut allowed = vec!["kind"];
        allowed.extend_from_slice(keys);
        cx.only(kind.what, &f, &present, &allowed)?;
    }
    let lt = Lt {
        cx,
        f,
        sp: sp.clone(),
        l,
        present,
        spectrum,
    };
    let (kind, spectrum) = (kind.read)(&lt)?;
    Ok(LightDesc {
        kind,
        spectrum,
        sampling_weight: 1.0,
        loc: cx.src.span(&sp),
    })
}
