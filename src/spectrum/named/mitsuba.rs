//! Mitsuba 3's conductor presets: its own n, k data files, read as Mitsuba reads them.

use std::sync::Arc;

use super::{Metal, Named, lookup, source_line};
use crate::spectrum::data::{embedded_table, table_to_curve};
use crate::spectrum::ior::ComplexIor;

pub(super) fn conductor(name: &str, f: (&str, &str)) -> Named {
    let t = embedded_table(f);
    let (n, k) = match (table_to_curve(&t, 0, 1, f.0), table_to_curve(&t, 0, 2, f.0)) {
        (Ok(n), Ok(k)) => (n, k),
        (Err(e), _) | (_, Err(e)) => panic!("embedded data file is corrupt: {e}"), // ok: invariant
    };
    let source = t
        .comment_starting("Mitsuba 3's documentation")
        .map(|_| {
            format!(
                "Mitsuba {} data/ior/{name}.eta.spd, .k.spd (Palik et al. via the Luxpop database)",
                MITSUBA_VERSION
            )
        })
        .unwrap_or_else(|| source_line(&t));
    Named::Conductor(Metal {
        name: name.into(),
        ior: ComplexIor {
            n: Arc::new(n),
            k: Arc::new(k),
        },
        source,
    })
}

/// The Mitsuba version whose conductor presets `mitsuba:<name>` reproduces.
pub const MITSUBA_VERSION: &str = "3.9.1";

/// The n, k that Mitsuba 3.9.1 uses for `<string name="material" value="NAME"/>` in a
/// `conductor` or `roughconductor`: its own data (`mitsuba:NAME`), matched case-sensitively as
/// Mitsuba opens `data/ior/NAME.eta.spd`. Mitsuba reads eta = k = 0 outside a file's wavelengths,
/// which is no metal; a preset whose data does not cover Mitsuba's 360–830 nm is refused.
/// Errors are a sentence for the user.
pub fn mitsuba_conductor(name: &str) -> Result<(ComplexIor, Option<String>), String> {
    let known = || {
        let mut v: Vec<&str> = crate::spectrum::data::embedded::MITSUBA_METALS
            .iter()
            .map(|m| m.0)
            .collect();
        v.sort_by_key(|n| n.to_lowercase());
        v.join(", ")
    };
    match lookup(&format!("mitsuba:{name}")) {
        Ok(Named::Conductor(m)) if m.name == name => {
            let (lo, hi) = (m.ior.n.domain(), m.ior.k.domain());
            let note = (lo.0 > 360.0 || hi.0 > 360.0 || lo.1 < 830.0 || hi.1 < 830.0).then(|| {
                format!(
                    "Mitsuba's data for material \"{name}\" covers only {}–{} nm; outside it Mitsuba 3.9.1 reads eta = k = 0, a perfect mirror, and so does spectrace (give eta and k for measured values there)",
                    lo.0.max(hi.0),
                    lo.1.min(hi.1)
                )
            });
            Ok((m.ior, note))
        }
        Ok(Named::Conductor(m)) => Err(format!(
            "material \"{name}\" is not one of Mitsuba's presets (names are case-sensitive): did you mean \"{}\"?",
            m.name
        )),
        _ => Err(format!(
            "material \"{name}\" is not one of Mitsuba 3.9.1's conductor presets ({}); or give eta and k",
            known()
        )),
    }
}
