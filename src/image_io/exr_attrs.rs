//! Names, text and header attributes between spectrace's plain types and the `exr` crate.
//!
//! A few attribute names are standard OpenEXR attributes that the `exr` crate keeps in typed
//! fields of `LayerAttributes` instead of its map of custom attributes (`owner`, `software`,
//! `expTime`, …). Those with a text or float value are mapped to and from their fields here, so
//! they round-trip like any other attribute. The other standard names (`channels`,
//! `dataWindow`, `chromaticities`, …) describe the file itself and are refused.

use std::collections::HashSet;
use std::path::Path;

use exr::meta::header::standard_names;
use exr::prelude::{AttributeValue, LayerAttributes, Text};

use super::{AttrValue, ImageError, invalid};

/// Longest channel or attribute name OpenEXR accepts (with the long-names flag).
const MAX_NAME_BYTES: usize = 255;

/// Checks a channel or attribute name: not empty, no NUL, at most 255 bytes.
pub(super) fn check_name(path: &Path, what: &str, name: &str) -> Result<(), ImageError> {
    if name.is_empty() {
        return Err(invalid(path, format!("{what} name is empty")));
    }
    if name.contains('\0') {
        return Err(invalid(
            path,
            format!("{what} name {name:?} contains a NUL character"),
        ));
    }
    if name.len() > MAX_NAME_BYTES {
        return Err(invalid(
            path,
            format!("{what} name {name:?} is longer than {MAX_NAME_BYTES} bytes"),
        ));
    }
    Ok(())
}

/// A string as EXR text: its UTF-8 bytes.
pub(super) fn to_text(s: &str) -> Text {
    Text::from_slice_unchecked(s.as_bytes())
}

/// EXR text as a string: UTF-8 if it is valid UTF-8, Latin-1 otherwise.
pub(super) fn from_text(t: &Text) -> String {
    let bytes = t.as_slice();
    match std::str::from_utf8(bytes) {
        Ok(s) => s.to_string(),
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    }
}

/// A standard attribute the `exr` crate keeps in a typed field.
enum Slot<'a> {
    Text(&'a mut Option<Text>),
    Float(&'a mut Option<f32>),
}

/// The standard attributes with a [`Slot`]; [`slot`] must know every one of them.
const SLOT_NAMES: [&str; 22] = [
    "owner",
    "comments",
    "capDate",
    "software",
    "renderingTransform",
    "lookModTransform",
    "wrapmodes",
    "view",
    "whiteLuminance",
    "xDensity",
    "utcOffset",
    "longitude",
    "latitude",
    "altitude",
    "focus",
    "expTime",
    "aperture",
    "isoSpeed",
    "near",
    "far",
    "fieldOfViewHorizontal",
    "fieldOfViewVertical",
];

fn slot<'a>(la: &'a mut LayerAttributes, name: &str) -> Option<Slot<'a>> {
    use Slot::{Float, Text};
    Some(match name {
        "owner" => Text(&mut la.owner),
        "comments" => Text(&mut la.comments),
        "capDate" => Text(&mut la.capture_date),
        "software" => Text(&mut la.software_name),
        "renderingTransform" => Text(&mut la.rendering_transform_name),
        "lookModTransform" => Text(&mut la.look_modification_transform_name),
        "wrapmodes" => Text(&mut la.wrap_mode_name),
        "view" => Text(&mut la.view_name),
        "whiteLuminance" => Float(&mut la.white_luminance),
        "xDensity" => Float(&mut la.horizontal_density),
        "utcOffset" => Float(&mut la.utc_offset),
        "longitude" => Float(&mut la.longitude),
        "latitude" => Float(&mut la.latitude),
        "altitude" => Float(&mut la.altitude),
        "focus" => Float(&mut la.focus),
        "expTime" => Float(&mut la.exposure),
        "aperture" => Float(&mut la.aperture),
        "isoSpeed" => Float(&mut la.iso_speed),
        "near" => Float(&mut la.near_clip_plane),
        "far" => Float(&mut la.far_clip_plane),
        "fieldOfViewHorizontal" => Float(&mut la.horizontal_field_of_view),
        "fieldOfViewVertical" => Float(&mut la.vertical_field_of_view),
        _ => return None,
    })
}

/// Builds the layer attributes of a single-layer file from the caller's attributes.
pub(super) fn layer_attributes(
    path: &Path,
    attributes: &[(&str, AttrValue)],
) -> Result<LayerAttributes, ImageError> {
    let mut la = LayerAttributes::default();
    let mut seen = HashSet::new();
    for (name, value) in attributes {
        check_name(path, "attribute", name)?;
        if !seen.insert(*name) {
            return Err(invalid(path, format!("attribute `{name}` is given twice")));
        }
        let wrong_type = |want: &str| {
            invalid(
                path,
                format!("standard attribute `{name}` must be {want}, not {value:?}"),
            )
        };
        match (slot(&mut la, name), value) {
            (Some(Slot::Text(field)), AttrValue::Text(t)) => *field = Some(to_text(t)),
            (Some(Slot::Text(_)), _) => return Err(wrong_type("text")),
            (Some(Slot::Float(field)), AttrValue::Float(v)) => *field = Some(*v),
            (Some(Slot::Float(_)), _) => return Err(wrong_type("a float")),
            (None, _) if standard_names::ALL.contains(&name.as_bytes()) => {
                return Err(invalid(
                    path,
                    format!("attribute `{name}` is a reserved OpenEXR attribute"),
                ));
            }
            (None, value) => {
                la.other.insert(to_text(name), to_exr(value));
            }
        }
    }
    Ok(la)
}

fn to_exr(value: &AttrValue) -> AttributeValue {
    match value {
        AttrValue::Text(t) => AttributeValue::Text(to_text(t)),
        AttrValue::Float(v) => AttributeValue::F32(*v),
        AttrValue::Double(v) => AttributeValue::F64(*v),
        AttrValue::Int(v) => AttributeValue::I32(*v),
    }
}

fn from_exr(value: &AttributeValue) -> Option<AttrValue> {
    Some(match value {
        AttributeValue::Text(t) => AttrValue::Text(from_text(t)),
        AttributeValue::F32(v) => AttrValue::Float(*v),
        AttributeValue::F64(v) => AttrValue::Double(*v),
        AttributeValue::I32(v) => AttrValue::Int(*v),
        _ => return None,
    })
}

/// The text, float, double and int attributes of a file, sorted by name.
pub(super) fn read_attributes<'a>(
    layer: &'a LayerAttributes,
    image_other: impl Iterator<Item = (&'a Text, &'a AttributeValue)>,
) -> Vec<(String, AttrValue)> {
    let mut out = Vec::new();
    let mut la = layer.clone();
    for name in SLOT_NAMES {
        match slot(&mut la, name) {
            Some(Slot::Text(Some(t))) => {
                out.push((name.to_string(), AttrValue::Text(from_text(t))))
            }
            Some(Slot::Float(Some(v))) => out.push((name.to_string(), AttrValue::Float(*v))),
            _ => {}
        }
    }
    for (name, value) in layer.other.iter().chain(image_other) {
        if let Some(v) = from_exr(value) {
            out.push((from_text(name), v));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_slot_name_has_a_field() {
        let mut la = LayerAttributes::default();
        for name in SLOT_NAMES {
            assert!(slot(&mut la, name).is_some(), "{name}");
            assert!(standard_names::ALL.contains(&name.as_bytes()), "{name}");
        }
    }

    #[test]
    fn text_is_utf8_with_latin1_fallback() {
        assert_eq!(from_text(&to_text("W·m⁻²")), "W·m⁻²");
        assert_eq!(from_text(&Text::from_slice_unchecked(&[0x57, 0xB7])), "W·");
    }
}
