//! `[film]`: size, samples, pixel filter (through the filter registry), spectral bins and
//! exposure.

use super::*;
use crate::film::filter::{KINDS, gaussian};
use crate::loader::convert::params::{Entry, inline_table, read_kind};

/// Largest accepted image side and pixel count.
const MAX_SIDE: i64 = 32_768;
const MAX_PIXELS: i64 = 1 << 28;

pub(super) fn film(cx: &Cx<'_>, f: Option<&S<RawFilm>>) -> R<FilmDesc> {
    let mut d = FilmDesc {
        width: 512,
        height: 512,
        spp: 16,
        filter: gaussian::Desc::native(1.5),
        spectral_bins: 0,
        exposure_ev: None,
        max_component: None,
        crop: None,
        loc: Default::default(),
    };
    let Some(f) = f else { return Ok(d) };
    d.loc = cx.src.span(&f.span());
    let f = f.get_ref();
    if let Some(w) = &f.width {
        d.width = cx.int(w, "film.width", 1, MAX_SIDE)? as u32;
    }
    if let Some(h) = &f.height {
        d.height = cx.int(h, "film.height", 1, MAX_SIDE)? as u32;
    }
    if (d.width as i64) * (d.height as i64) > MAX_PIXELS {
        let span = f
            .height
            .as_ref()
            .or(f.width.as_ref())
            .map(|v| v.span())
            .unwrap_or(WHOLE_FILE);
        return Err(cx.err(
            &span,
            "film",
            format!(
                "{}×{} pixels is more than the {MAX_PIXELS} supported",
                d.width, d.height
            ),
        ));
    }
    if let Some(s) = &f.spp {
        d.spp = cx.int(s, "film.spp", 1, 1 << 24)? as u32;
    }
    if let Some(b) = &f.spectral_bins {
        d.spectral_bins = cx.int(b, "film.spectral_bins", 0, 1000)? as u32;
    }
    if let Some(e) = &f.exposure {
        d.exposure_ev = Some(cx.number(e, "film.exposure")?);
    }
    d.filter = filter(cx, f)?;
    Ok(d)
}

/// `film.filter`: a kind's name with its radius in `filter_radius`, or an inline table
/// `{ type = "NAME", … }` of the kind's own parameters; spectrace's Gaussian if absent.
fn filter(cx: &Cx<'_>, f: &RawFilm) -> R<FilterDesc> {
    let (name, name_span, entries) = match &f.filter {
        None => ("gaussian", WHOLE_FILE, Vec::new()),
        Some(v) => match v.get_ref() {
            Value::String(s) => (s.as_str(), v.span(), Vec::new()),
            Value::Table(t) => {
                let (name, entries) = inline_table(cx, t, &v.span(), "film.filter")?;
                (name, v.span(), entries)
            }
            _ => {
                return Err(cx.err(
                    &v.span(),
                    "film.filter",
                    "expected a filter name or a table { type = \"NAME\", … }",
                ));
            }
        },
    };
    let mut entries = entries;
    if let Some(r) = &f.filter_radius {
        if entries.iter().any(|e| e.name == "radius") {
            return Err(cx.err(
                &r.span(),
                "film.filter_radius",
                "the filter's table gives its radius already",
            ));
        }
        entries.push(Entry {
            name: "radius".into(),
            field: "film.filter_radius".into(),
            value: r.get_ref().clone(),
            span: r.span(),
        });
    }
    read_kind(
        cx,
        KINDS,
        "filter",
        "film.filter",
        name,
        &name_span,
        &entries,
    )
}
