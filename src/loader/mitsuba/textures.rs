//! Mitsuba textures: a property that may be a `<texture>` (`checkerboard`, `bitmap`), a `<ref>`
//! to one declared at the top level, or a plain spectrum. Read as Mitsuba 3.9.1 reads them
//! (`src/textures/checkerboard.cpp`, `bitmap.cpp`; see `crate::texture`).

use super::cx::{Cx, R};
use super::xml::Element;
use crate::loader::desc::{TexFilter, TextureDesc, Wrap};
use crate::spectrum::Spectrum;

impl Cx<'_> {
    /// The texture or spectrum of child `name` of `e`, `default` when absent (a reflectance:
    /// not an emitter's spectrum).
    pub(super) fn texture_prop(&self, e: &Element, name: &str, default: f32) -> R<TextureDesc> {
        let Some(c) = self.child(e, name) else {
            return Ok(Spectrum::Constant(default).into());
        };
        self.texture_of(c)
    }

    /// [`Cx::texture_prop`] for a property Mitsuba reads as one number (`eval_1`: roughness,
    /// opacity, a blend weight). Mitsuba 3.9.1's checkerboard gives `color0` there on the checks
    /// where its spectral `eval` gives `color1` (`checkerboard.cpp`: `m0 = mask.x != mask.y` in
    /// `eval_1`, `==` in `eval`), so a checkerboard read this way has its colours swapped.
    pub(super) fn scalar_texture_prop(
        &self,
        e: &Element,
        name: &str,
        default: f32,
    ) -> R<TextureDesc> {
        Ok(match self.texture_prop(e, name, default)? {
            TextureDesc::Checkerboard { a, b, to_uv } => {
                TextureDesc::Checkerboard { a: b, b: a, to_uv }
            }
            t => t,
        })
    }

    /// The texture (or spectrum) a property element `c` gives.
    pub(super) fn texture_of(&self, c: &Element) -> R<TextureDesc> {
        let t = self.resolve(c)?;
        if t.tag != "texture" {
            return Ok(self.spectrum(c, false)?.into());
        }
        let to_uv = match t
            .children
            .iter()
            .find(|c| c.tag == "transform" && c.attr("name") == Some("to_uv"))
        {
            Some(tr) => self.transform(tr)?,
            None => Vec::new(),
        };
        match t.attr("type").unwrap_or("") {
            "checkerboard" => {
                let colour = |key: &str, default: f32| -> R<Spectrum> {
                    match self.child(t, key) {
                        Some(c) if self.resolve(c)?.tag == "texture" => Err(self.err(
                            c,
                            "a checkerboard's colours are spectra here, not nested textures",
                        )),
                        Some(c) => self.spectrum(c, false),
                        None => Ok(Spectrum::Constant(default)),
                    }
                };
                Ok(TextureDesc::Checkerboard {
                    a: colour("color0", 0.4)?,
                    b: colour("color1", 0.2)?,
                    to_uv,
                })
            }
            "bitmap" => {
                let f = self
                    .string(t, "filename")
                    .ok_or_else(|| self.err(t, "missing filename"))?;
                let path = self.resolve_file(&f);
                if !path.is_file() {
                    return Err(
                        self.err(t, format!("image file {} does not exist", path.display()))
                    );
                }
                // errors about a property point at its element
                let at = |key: &str| self.child(t, key).unwrap_or(t);
                let filter = match self.string(t, "filter_type").as_deref() {
                    None | Some("bilinear") => TexFilter::Bilinear,
                    Some("nearest") => TexFilter::Nearest,
                    Some(o) => {
                        return Err(self.err(
                            at("filter_type"),
                            format!("filter_type \"{o}\" is not one of \"bilinear\", \"nearest\""),
                        ));
                    }
                };
                let wrap = self.wrap_mode(t, Wrap::Repeat)?;
                let raw = match self.string(t, "raw").as_deref() {
                    None | Some("false") => false,
                    Some("true") => true,
                    Some(o) => {
                        return Err(
                            self.err(at("raw"), format!("raw: expected true or false, found {o}"))
                        );
                    }
                };
                Ok(TextureDesc::Bitmap {
                    path,
                    filter,
                    wrap,
                    raw,
                    to_uv,
                    loc: self.loc(t),
                })
            }
            // numbers as given, neither a colour nor uplifted (`rawconstant.cpp`)
            "rawconstant" => {
                let v = self
                    .child(t, "value")
                    .ok_or_else(|| self.err(t, "a rawconstant needs a value"))?;
                let v = match v.tag.as_str() {
                    "vector" | "point" => self.vec3(v)?,
                    _ => [self.float(v)?; 3],
                };
                Ok(TextureDesc::Raw(v.map(|x| x as f32)))
            }
            // a mesh's attribute by name (`mesh_attribute.cpp`)
            "mesh_attribute" => {
                let at = |key: &str| self.child(t, key).unwrap_or(t);
                let name = self
                    .string(t, "name")
                    .ok_or_else(|| self.err(t, "a mesh_attribute needs a name"))?;
                if !(name.starts_with("vertex_") || name.starts_with("face_")) {
                    return Err(self.err(
                        at("name"),
                        format!(
                            "a mesh attribute's name starts with vertex_ or face_, not \"{name}\""
                        ),
                    ));
                }
                let scale = self.opt_float(t, "scale")?.unwrap_or(1.0);
                if !scale.is_finite() {
                    return Err(self.err(at("scale"), format!("scale must be finite, not {scale}")));
                }
                Ok(TextureDesc::MeshAttribute { name, scale })
            }
            other => Err(self.unsupported(t, "texture", other)),
        }
    }
}

impl Cx<'_> {
    /// `e`'s `wrap_mode` (`repeat`, `mirror`, `clamp`; `default` when absent), as bitmaps and
    /// grid volumes read it.
    pub(super) fn wrap_mode(&self, e: &Element, default: Wrap) -> R<Wrap> {
        Ok(match self.string(e, "wrap_mode").as_deref() {
            None => default,
            Some("repeat") => Wrap::Repeat,
            Some("mirror") => Wrap::Mirror,
            Some("clamp") => Wrap::Clamp,
            Some(o) => {
                let at = self.child(e, "wrap_mode").unwrap_or(e);
                return Err(self.err(
                    at,
                    format!("wrap_mode \"{o}\" is not one of \"repeat\", \"mirror\", \"clamp\""),
                ));
            }
        })
    }
}
