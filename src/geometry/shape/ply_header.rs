//! A PLY file's header: its format, elements and their properties' types.

use crate::geometry::error::GeometryError;

#[derive(Clone, Copy, PartialEq)]
pub(super) enum Format {
    Ascii,
    Le,
    Be,
}

#[derive(Clone, Copy)]
pub(super) enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Ty {
    fn parse(s: &str) -> Option<Ty> {
        Some(match s {
            "char" | "int8" => Ty::I8,
            "uchar" | "uint8" => Ty::U8,
            "short" | "int16" => Ty::I16,
            "ushort" | "uint16" => Ty::U16,
            "int" | "int32" => Ty::I32,
            "uint" | "uint32" => Ty::U32,
            "float" | "float32" => Ty::F32,
            "double" | "float64" => Ty::F64,
            _ => return None,
        })
    }
    pub(super) fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::F64 => 8,
        }
    }
}

pub(super) struct Prop {
    pub(super) name: String,
    pub(super) ty: Ty,
    /// Some(count type) for list properties.
    pub(super) list: Option<Ty>,
}

pub(super) struct Elem {
    pub(super) name: String,
    pub(super) count: usize,
    pub(super) props: Vec<Prop>,
}

/// The header's text and where the body starts (after `end_header` and its line end).
pub(super) fn split_header<'a>(
    bytes: &'a [u8],
    bad: &dyn Fn(&str) -> GeometryError,
) -> Result<(&'a str, usize), GeometryError> {
    let end = bytes
        .windows(10)
        .position(|w| w == b"end_header")
        .ok_or_else(|| bad("no end_header"))?;
    let header = std::str::from_utf8(&bytes[..end]).map_err(|_| bad("the header is not text"))?;
    let mut body_start = end + 10;
    while body_start < bytes.len() && (bytes[body_start] == b'\r' || bytes[body_start] == b'\n') {
        body_start += 1;
        if bytes[body_start - 1] == b'\n' {
            break;
        }
    }
    Ok((header, body_start))
}

/// The PLY header's format and elements (with their properties); `bad` makes the error.
pub(super) fn parse_header(
    header: &str,
    bad: &dyn Fn(&str) -> GeometryError,
) -> Result<(Format, Vec<Elem>), GeometryError> {
    let mut lines = header.lines();
    if lines.next().map(str::trim) != Some("ply") {
        return Err(bad("not a PLY file (no 'ply' magic)"));
    }
    let mut format = None;
    let mut elems: Vec<Elem> = Vec::new();
    for line in lines {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["format", f, _] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Le,
                    "binary_big_endian" => Format::Be,
                    _ => return Err(bad(&format!("unknown format {f}"))),
                })
            }
            ["element", name, count] => elems.push(Elem {
                name: name.to_string(),
                count: count
                    .parse()
                    .map_err(|_| bad(&format!("bad element count {count}")))?,
                props: Vec::new(),
            }),
            ["property", "list", ct, ty, name] => {
                let (Some(ct), Some(ty)) = (Ty::parse(ct), Ty::parse(ty)) else {
                    return Err(bad(&format!("unknown type in '{line}'")));
                };
                add_prop(&mut elems, name, ty, Some(ct), bad)?;
            }
            ["property", ty, name] => {
                let ty = Ty::parse(ty).ok_or_else(|| bad(&format!("unknown type in '{line}'")))?;
                add_prop(&mut elems, name, ty, None, bad)?;
            }
            _ => {}
        }
    }
    let format = format.ok_or_else(|| bad("no format line"))?;
    Ok((format, elems))
}

/// Adds a property to the last element declared; an error if none was.
fn add_prop(
    elems: &mut [Elem],
    name: &str,
    ty: Ty,
    list: Option<Ty>,
    bad: &dyn Fn(&str) -> GeometryError,
) -> Result<(), GeometryError> {
    let e = elems
        .last_mut()
        .ok_or_else(|| bad("property before element"))?;
    e.props.push(Prop {
        name: name.to_string(),
        ty,
        list,
    });
    Ok(())
}
