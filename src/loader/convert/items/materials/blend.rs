//! `type = "blend"`: Mitsuba's `blendbsdf`, (1 − `weight`)·the first of `materials` +
//! `weight`·the second (`weight` a number or a grey texture in [0, 1], default 0.5).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "blend",
    keys: &["weight", "materials"],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let what = "the names of the two blended materials, [\"a\", \"b\"]";
    let v = m.required("materials", what)?;
    let names: Vec<S<String>> = match v.get_ref() {
        Value::Array(a) if a.iter().all(Value::is_str) => {
            // each name located where it stands in the array (errors point at it)
            let mut from = v.span().start;
            a.iter()
                .filter_map(|n| n.as_str())
                .map(|n| {
                    let at = m.cx.src.find_in(&v.span(), from, &format!("\"{n}\""));
                    from = at.end;
                    S::new(at, n.to_string())
                })
                .collect()
        }
        _ => {
            return Err(m
                .cx
                .err(&v.span(), m.field("materials"), format!("expected {what}")));
        }
    };
    let [a, b] = &names[..] else {
        return Err(m.cx.err(
            &v.span(),
            m.field("materials"),
            format!("expected the names of two materials, found {}", names.len()),
        ));
    };
    let not = ["mask", "blend"];
    let held = "another mask or blend";
    let a = m.named(a, "materials", "a blend", &not, held)?;
    let b = m.named(b, "materials", "a blend", &not, held)?;
    Ok(MaterialKind::Blend {
        weight: m.texture_or("weight", 0.5)?,
        a: Box::new(a),
        b: Box::new(b),
    })
}
