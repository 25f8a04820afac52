//! `[[sensors]]`: irradiance and illuminance meters at a point or on a grid of points.

use super::*;

pub(super) fn sensor(cx: &Cx<'_>, i: usize, s: &S<RawSensor>) -> R<SensorDesc> {
    let sp = s.span();
    let f = format!("sensors[{i}]");
    let s = s.get_ref();
    let all = present!(s; kind, name, position, normal, corner, edge_u, edge_v, count);
    let ty = cx.required(&s.kind, &sp, &format!("{f}.type"), "point or grid")?;
    let name = match &s.name {
        Some(n) => {
            let v = n.get_ref().trim();
            if v.is_empty() || v.contains([',', '"', '\n']) {
                return Err(cx.err(
                    &n.span(),
                    format!("{f}.name"),
                    "a sensor name must not be empty or hold commas, quotes or line breaks (it becomes a CSV field)",
                ));
            }
            v.to_string()
        }
        None => format!("sensor{i}"),
    };
    let kind = match ty.get_ref().as_str() {
        "point" => {
            cx.only(
                "a point sensor",
                &f,
                &all,
                &["kind", "name", "position", "normal"],
            )?;
            let p = cx.required(&s.position, &sp, &format!("{f}.position"), "[x, y, z]")?;
            SensorKind::Point {
                position: cx.point(p, &format!("{f}.position"))?,
                normal: normal(cx, s, &sp, &f, None)?,
            }
        }
        "grid" => grid(cx, s, &sp, &f, &all)?,
        o => {
            return Err(cx.err(
                &ty.span(),
                format!("{f}.type"),
                format!("unknown sensor type \"{o}\"; expected point or grid"),
            ));
        }
    };
    Ok(SensorDesc {
        name,
        kind,
        loc: cx.src.span(&sp),
    })
}

/// A sensor's `normal` (not zero), or `default` where the kind has one.
fn normal(
    cx: &Cx<'_>,
    s: &RawSensor,
    sp: &Range<usize>,
    f: &str,
    default: Option<[f64; 3]>,
) -> R<[f64; 3]> {
    let n = match (&s.normal, default) {
        (Some(v), _) => (cx.vec3(v, &format!("{f}.normal"))?, v.span()),
        (None, Some(d)) => return Ok(d),
        (None, None) => {
            return Err(cx.err(
                sp,
                format!("{f}.normal"),
                "missing: the side the meter measures, [x, y, z]",
            ));
        }
    };
    if n.0 == [0.0; 3] {
        return Err(cx.err(&n.1, format!("{f}.normal"), "the normal is zero"));
    }
    Ok(n.0)
}

/// A grid sensor: a corner, two edges (not parallel) and the points along each.
fn grid(
    cx: &Cx<'_>,
    s: &RawSensor,
    sp: &Range<usize>,
    f: &str,
    all: &[(&str, Range<usize>)],
) -> R<SensorKind> {
    cx.only(
        "a grid sensor",
        f,
        all,
        &[
            "kind", "name", "corner", "edge_u", "edge_v", "count", "normal",
        ],
    )?;
    let get = |v: &Option<S<Value>>, key: &str, what: &str| -> R<Point> {
        let x = cx.required(v, sp, &format!("{f}.{key}"), what)?;
        cx.point(x, &format!("{f}.{key}"))
    };
    let corner = get(&s.corner, "corner", "a corner of the grid [x, y, z]")?;
    let edge_u = get(
        &s.edge_u,
        "edge_u",
        "the grid's first edge, a vector [x, y, z]",
    )?;
    let edge_v = get(
        &s.edge_v,
        "edge_v",
        "the grid's second edge, a vector [x, y, z]",
    )?;
    let m = |p: &Point| p.map(|x| x.get::<length::meter>());
    let (a, b) = (m(&edge_u), m(&edge_v));
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let area2: f64 = cross.iter().map(|x| x * x).sum();
    let len2 = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>();
    if !(area2 > 1e-12 * len2(a) * len2(b)) {
        return Err(cx.err(
            sp,
            format!("{f}.edge_v"),
            "the grid's edges are zero or parallel",
        ));
    }
    let c = cx.required(
        &s.count,
        sp,
        &format!("{f}.count"),
        "[nu, nv], points along each edge",
    )?;
    let Value::Array(arr) = c.get_ref() else {
        return Err(cx.err(&c.span(), format!("{f}.count"), "expected [nu, nv]"));
    };
    let counts: Vec<i64> = arr.iter().filter_map(|v| v.as_integer()).collect();
    if counts.len() != 2
        || arr.len() != 2
        || counts.iter().any(|&n| !(1..=10_000).contains(&n))
        || counts[0] * counts[1] > 1_000_000
    {
        return Err(cx.err(
            &c.span(),
            format!("{f}.count"),
            "expected [nu, nv], two whole numbers from 1 to 10000 with at most 1000000 points in all",
        ));
    }
    Ok(SensorKind::Grid {
        corner,
        edge_u,
        edge_v,
        count: [counts[0] as u32, counts[1] as u32],
        normal: normal(cx, s, sp, f, Some(cross))?,
    })
}
