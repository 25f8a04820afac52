//! `type = "normal_map"` and `"bump_map"`: Mitsuba's `normalmap` and `bumpmap` around the
//! material named by `material`: `map` an image of normals encoded (n + 1)/2, or `height` a
//! grey image times `scale` (default 1); both images read as stored numbers (Mitsuba's
//! raw = true), not decoded from sRGB.

use super::*;

pub(super) const NORMAL_MAP: Kind = Kind {
    name: "normal_map",
    keys: &["map", "material"],
    read: |m| read(m, true),
};

pub(super) const BUMP_MAP: Kind = Kind {
    name: "bump_map",
    keys: &["height", "scale", "material"],
    read: |m| read(m, false),
};

fn read(m: &Mat<'_>, normal: bool) -> R<MaterialKind> {
    let (key, what) = if normal {
        ("map", "a normal map material")
    } else {
        ("height", "a bump map material")
    };
    let t = m.required(
        key,
        "an image: { image = \"file.png\" } with optional filter, wrap and scale",
    )?;
    let tex = match m.texture(t, key)?.raw() {
        t @ TextureDesc::Bitmap { .. } => t,
        _ => {
            return Err(m.cx.err(
                &t.span(),
                m.field(key),
                "expected an image: { image = \"file.png\" }",
            ));
        }
    };
    let (name, inner) = m.named_at(
        "material",
        "the name of the material the map perturbs",
        what,
        &["mask", "blend"],
        "another mask or blend",
    )?;
    if matches!(
        inner,
        MaterialKind::NormalMap { .. } | MaterialKind::BumpMap { .. }
    ) {
        return Err(m.cx.err(
            &name.span(),
            m.field("material"),
            format!("{what} cannot hold another normal or bump map"),
        ));
    }
    let inner = Box::new(inner);
    if normal {
        return Ok(MaterialKind::NormalMap {
            map: tex,
            inner,
            pbrt: false,
        });
    }
    let scale = match m.get("scale") {
        Some(v) => m.number(v, "scale")?,
        None => 1.0,
    };
    Ok(MaterialKind::BumpMap {
        height: tex,
        scale,
        inner,
        pbrt: false,
    })
}
