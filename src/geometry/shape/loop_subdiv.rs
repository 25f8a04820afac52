//! Loop subdivision (Loop 1987, "Smooth Subdivision Surfaces Based on Triangles"), as pbrt
//! defines its `loopsubdiv` shape (pbrt-v3 book §3.8; pbrt-v4 `src/pbrt/util/loopsubdiv.cpp`):
//! `levels` rounds of splitting every triangle in four, then every vertex moved to its limit
//! position, with the limit surface's normal as its shading normal.
//!
//! The rules, with n a vertex's valence (its neighbours' count):
//! - an old interior vertex: (1 − nβ)·v + β·Σ neighbours, β = 3/16 for n = 3, else 3/(8n);
//!   an old boundary vertex: 3/4·v + 1/8·(its two boundary neighbours);
//! - a new vertex on an interior edge: 3/8 of each end and 1/8 of each opposite vertex; on a
//!   boundary edge, its midpoint;
//! - the limit position: the interior rule with γ = 1/(n + 3/(8β)) in β's place; on the
//!   boundary 3/5·v + 1/5·(the boundary neighbours);
//! - the limit normal: the cross product of the tangents Σ cos(2πj/n)·rⱼ and Σ sin(2πj/n)·rⱼ
//!   over the ordered ring rⱼ; on the boundary, the chord between the boundary neighbours and
//!   pbrt's cross-boundary tangent for each valence. Each normal is oriented to the side of
//!   the faces around the vertex (their counter-clockwise winding).
//!
//! Failure: a mesh that is not a consistently oriented 2-manifold (an edge in more than two
//! triangles, or twice in the same direction) is an error naming the edge.

use std::collections::HashMap;
use std::f64::consts::PI;

use glam::DVec3;

/// A subdivided mesh: positions, unit shading normals (one per position) and triangles.
pub struct Subdivided {
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// Each vertex's ring of neighbours, in counter-clockwise order (seen with the faces' winding
/// counter-clockwise), and whether it lies on the boundary (then the ring runs from one
/// boundary neighbour to the other).
struct Rings {
    ring: Vec<Vec<u32>>,
    boundary: Vec<bool>,
}

fn rings(n_vertices: usize, tris: &[[u32; 3]]) -> Result<Rings, String> {
    // the link of each vertex: for a face (v, a, b), the step a → b around v
    let mut link: Vec<Vec<(u32, u32)>> = vec![Vec::new(); n_vertices];
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for t in tris {
        for k in 0..3 {
            let (v, a, b) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            link[v as usize].push((a, b));
            if directed.insert((v, a), 1).is_some() {
                return Err(format!(
                    "the edge {v}–{a} is in two triangles in the same direction (the mesh is not consistently oriented or not a 2-manifold)"
                ));
            }
        }
    }
    let mut ring = Vec::with_capacity(n_vertices);
    let mut boundary = Vec::with_capacity(n_vertices);
    for (v, l) in link.iter().enumerate() {
        if l.is_empty() {
            ring.push(Vec::new());
            boundary.push(false);
            continue;
        }
        let next: HashMap<u32, u32> = l.iter().copied().collect();
        // a boundary vertex's ring starts where no step arrives
        let start = l
            .iter()
            .map(|&(a, _)| a)
            .find(|a| !l.iter().any(|&(_, b)| b == *a));
        let first = start.unwrap_or(l[0].0);
        let mut r = vec![first];
        let mut cur = first;
        while let Some(&nx) = next.get(&cur) {
            if nx == first {
                break;
            }
            if r.len() > l.len() {
                return Err(format!(
                    "the faces around vertex {v} do not form one fan (the mesh is not a 2-manifold there)"
                ));
            }
            r.push(nx);
            cur = nx;
        }
        let expected = if start.is_some() {
            l.len() + 1
        } else {
            l.len()
        };
        if r.len() != expected {
            return Err(format!(
                "the faces around vertex {v} do not form one fan (the mesh is not a 2-manifold there)"
            ));
        }
        ring.push(r);
        boundary.push(start.is_some());
    }
    Ok(Rings { ring, boundary })
}

/// Loop's β for valence n.
fn beta(n: usize) -> f64 {
    if n == 3 {
        3.0 / 16.0
    } else {
        3.0 / (8.0 * n as f64)
    }
}

/// The interior rule with weight `b` per neighbour, or the boundary rule with weight `bb` on
/// each boundary neighbour.
fn smooth(p: &[DVec3], v: usize, r: &Rings, b: f64, bb: f64) -> DVec3 {
    let ring = &r.ring[v];
    if ring.is_empty() {
        return p[v];
    }
    if r.boundary[v] {
        let (a, z) = (p[ring[0] as usize], p[*ring.last().unwrap() as usize]);
        (1.0 - 2.0 * bb) * p[v] + bb * (a + z)
    } else {
        let s: DVec3 = ring.iter().map(|&j| p[j as usize]).sum();
        (1.0 - ring.len() as f64 * b) * p[v] + b * s
    }
}

/// One round: every triangle split in four.
fn step(p: &[DVec3], tris: &[[u32; 3]]) -> Result<(Vec<DVec3>, Vec<[u32; 3]>), String> {
    let r = rings(p.len(), tris)?;
    let mut out: Vec<DVec3> = (0..p.len())
        .map(|v| smooth(p, v, &r, beta(r.ring[v].len()), 1.0 / 8.0))
        .collect();
    // the opposite vertices of each undirected edge
    let mut opposite: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
    for t in tris {
        for k in 0..3 {
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            opposite.entry((a.min(b), a.max(b))).or_default().push(c);
        }
    }
    let mut edge_vertex: HashMap<(u32, u32), u32> = HashMap::new();
    let mut mid = |a: u32, b: u32, out: &mut Vec<DVec3>| -> Result<u32, String> {
        let key = (a.min(b), a.max(b));
        if let Some(&i) = edge_vertex.get(&key) {
            return Ok(i);
        }
        let (pa, pb) = (p[a as usize], p[b as usize]);
        let q = match opposite[&key][..] {
            [_] => 0.5 * (pa + pb),
            [c, d] => 3.0 / 8.0 * (pa + pb) + 1.0 / 8.0 * (p[c as usize] + p[d as usize]),
            _ => return Err(format!("the edge {a}–{b} is in more than two triangles")),
        };
        out.push(q);
        let i = (out.len() - 1) as u32;
        edge_vertex.insert(key, i);
        Ok(i)
    };
    let mut new_tris = Vec::with_capacity(tris.len() * 4);
    for t in tris {
        let [a, b, c] = *t;
        let (ab, bc, ca) = (
            mid(a, b, &mut out)?,
            mid(b, c, &mut out)?,
            mid(c, a, &mut out)?,
        );
        new_tris.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
    }
    Ok((out, new_tris))
}

/// The limit normal at `v` (not normalised, not oriented).
fn limit_normal(p: &[DVec3], v: usize, r: &Rings) -> DVec3 {
    let ring: Vec<DVec3> = r.ring[v].iter().map(|&j| p[j as usize]).collect();
    let n = ring.len();
    if n == 0 {
        return DVec3::ZERO;
    }
    if !r.boundary[v] {
        let (mut s, mut t) = (DVec3::ZERO, DVec3::ZERO);
        for (j, q) in ring.iter().enumerate() {
            let a = 2.0 * PI * j as f64 / n as f64;
            s += a.cos() * *q;
            t += a.sin() * *q;
        }
        return s.cross(t);
    }
    let pv = p[v];
    let s = ring[n - 1] - ring[0];
    let t = match n {
        2 => ring[0] + ring[1] - 2.0 * pv,
        3 => ring[1] - pv,
        4 => -ring[0] + 2.0 * ring[1] + 2.0 * ring[2] - ring[3] - 2.0 * pv,
        _ => {
            let th = PI / (n - 1) as f64;
            let mut t = th.sin() * (ring[0] + ring[n - 1]);
            for (k, q) in ring.iter().enumerate().take(n - 1).skip(1) {
                t += (2.0 * th.cos() - 2.0) * (k as f64 * th).sin() * *q;
            }
            -t
        }
    };
    s.cross(t)
}

/// `levels` rounds of Loop subdivision of `positions` and counter-clockwise `triangles`, then
/// the limit surface's positions and normals (see the module's docs).
pub fn loop_subdivide(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    levels: u32,
) -> Result<Subdivided, String> {
    let (mut p, mut tris) = (positions.to_vec(), triangles.to_vec());
    for _ in 0..levels {
        (p, tris) = step(&p, &tris)?;
    }
    let r = rings(p.len(), &tris)?;
    let limit: Vec<DVec3> = (0..p.len())
        .map(|v| {
            let n = r.ring[v].len();
            let b = beta(n);
            smooth(&p, v, &r, 1.0 / (n as f64 + 3.0 / (8.0 * b)), 1.0 / 5.0)
        })
        .collect();
    // the faces' side at each vertex, to orient the limit normals
    let mut side = vec![DVec3::ZERO; p.len()];
    for t in &tris {
        let [a, b, c] = t.map(|i| limit[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            side[i as usize] += n;
        }
    }
    let normals = (0..p.len())
        .map(|v| {
            let n = limit_normal(&limit, v, &r);
            let n = if n.dot(side[v]) < 0.0 { -n } else { n };
            n.try_normalize()
                .or_else(|| side[v].try_normalize())
                .unwrap_or(DVec3::Z)
        })
        .collect();
    Ok(Subdivided {
        positions: limit,
        normals,
        triangles: tris,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn octahedron() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let p = vec![
            DVec3::X,
            DVec3::Y,
            DVec3::NEG_X,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ];
        let t = vec![
            [0, 1, 4],
            [1, 2, 4],
            [2, 3, 4],
            [3, 0, 4],
            [1, 0, 5],
            [2, 1, 5],
            [3, 2, 5],
            [0, 3, 5],
        ];
        (p, t)
    }

    /// A regular octahedron's limit surface is symmetric: every original vertex (valence 4)
    /// lands at the same distance from the centre, with its normal radial; the edge rule and
    /// the limit rule agree with hand-computed values.
    #[test]
    fn octahedron_limit_is_symmetric_and_matches_hand_values() {
        let (p, t) = octahedron();
        // level 0: γ(4) = 1/(4 + 3/(8·3/32)) = 1/8; the limit of (1,0,0) is 1/2·(1,0,0) + 1/8·(0,0,0)… = (1/2, 0, 0)
        let s = loop_subdivide(&p, &t, 0).unwrap();
        assert!((s.positions[0] - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-12);
        assert!((s.normals[0] - DVec3::X).length() < 1e-12);
        let s = loop_subdivide(&p, &t, 2).unwrap();
        assert_eq!(s.triangles.len(), 8 * 16);
        let r0 = s.positions[0].length();
        for (v, corner) in p.iter().enumerate() {
            assert!((s.positions[v].length() - r0).abs() < 1e-12);
            assert!(
                (s.normals[v] - *corner).length() < 1e-9,
                "{v}: {:?}",
                s.normals[v]
            );
        }
    }

    /// On a flat open patch every vertex stays in the plane, and the normals are the plane's.
    #[test]
    fn a_flat_patch_stays_flat_with_boundary_rules() {
        let p = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let s = loop_subdivide(&p, &[[0, 1, 2], [0, 2, 3]], 3).unwrap();
        for (q, n) in s.positions.iter().zip(&s.normals) {
            assert!(
                q.z.abs() < 1e-12 && (*n - DVec3::Z).length() < 1e-9,
                "{q:?} {n:?}"
            );
        }
        // a boundary corner of valence 3: 3/5·v + 1/5 of its boundary neighbours after the rounds
        assert!(s.positions[0].x > 0.0 && s.positions[0].x < 0.2);
    }

    #[test]
    fn inconsistent_orientation_is_an_error() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let e = loop_subdivide(&p, &[[0, 1, 2], [0, 1, 3]], 1)
            .err()
            .unwrap();
        assert!(e.contains("0–1"), "{e}");
    }
}
