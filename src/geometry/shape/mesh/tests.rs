//! Tests of `mesh`.

use super::*;

/// Triangles of a closed convex polyhedron centred at the origin, wound outward.
fn outward(positions: &[Vec3], tris: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
    tris.into_iter()
        .map(|t| {
            let p = t.map(|i| positions[i as usize]);
            let n = (p[1] - p[0]).cross(p[2] - p[0]);
            if n.dot(p[0] + p[1] + p[2]) < 0.0 {
                [t[0], t[2], t[1]]
            } else {
                t
            }
        })
        .collect()
}

#[test]
fn regular_icosahedron_has_radial_vertex_normals() {
    // a tessellated sphere whose vertices all see the same fan of 5 triangles: by symmetry
    // the angle-weighted normal is exactly radial
    let phi = (1.0 + 5f32.sqrt()) / 2.0;
    let mut ps = Vec::new();
    for a in [-1.0, 1.0] {
        for b in [-phi, phi] {
            ps.push(Vec3::new(0.0, a, b));
            ps.push(Vec3::new(a, b, 0.0));
            ps.push(Vec3::new(b, 0.0, a));
        }
    }
    // faces: the triples of vertices at mutual distance 2 (the edge length)
    let edge = |i: usize, j: usize| ((ps[i] - ps[j]).length() - 2.0).abs() < 1e-4;
    let mut tris = Vec::new();
    for i in 0..12 {
        for j in i + 1..12 {
            for k in j + 1..12 {
                if edge(i, j) && edge(j, k) && edge(i, k) {
                    tris.push([i as u32, j as u32, k as u32]);
                }
            }
        }
    }
    assert_eq!(tris.len(), 20);
    let ns = angle_weighted_normals(&ps, &outward(&ps, tris));
    for (p, n) in ps.iter().zip(&ns) {
        assert!((*n - p.normalize()).length() < 1e-6, "{p}: {n}");
    }
}

#[test]
fn cube_corner_normal_is_the_diagonal_whatever_the_triangulation() {
    // 8 shared corners; the +x face is split along the other diagonal, so the corner
    // (1, 1, 1) lies in one triangle there (90°) and in two on the +y and +z faces (45°
    // each). Weighting by angle gives (1, 1, 1)/√3 exactly; by count or by area it would
    // give (1, 2, 2)/3.
    let ps: Vec<Vec3> = (0..8)
        .map(|i| {
            let s = |b: u32| if i >> b & 1 == 1 { 1.0 } else { -1.0 };
            Vec3::new(s(0), s(1), s(2))
        })
        .collect();
    let corner = |v: [f32; 3]| ps.iter().position(|p| *p == Vec3::from(v)).unwrap() as u32;
    let mut tris = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let quad = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(b, c)| {
                let mut v = [0.0; 3];
                v[axis] = sign;
                v[(axis + 1) % 3] = b;
                v[(axis + 2) % 3] = c;
                corner(v)
            });
            if axis == 0 && sign > 0.0 {
                tris.push([quad[1], quad[2], quad[3]]);
                tris.push([quad[1], quad[3], quad[0]]);
            } else {
                tris.push([quad[0], quad[1], quad[2]]);
                tris.push([quad[0], quad[2], quad[3]]);
            }
        }
    }
    let ns = angle_weighted_normals(&ps, &outward(&ps, tris));
    for (p, n) in ps.iter().zip(&ns) {
        assert!((*n - p.normalize()).length() < 1e-6, "{p}: {n}");
    }
}

#[test]
fn folded_quad_matches_mitsuba() {
    // a quad folded along its diagonal, as a PLY without normals; the normals Mitsuba
    // 3.9.1 computes for it (`mi.load_dict({'type': 'ply', ...}).vertex_normals_buffer()`)
    let ps = vec![
        Vec3::ZERO,
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.5),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let ns = angle_weighted_normals(&ps, &[[0, 1, 2], [0, 2, 3]]);
    let mitsuba = [
        Vec3::new(-0.23570226, -0.23570226, 0.94280905),
        Vec3::new(0.0, -0.4472136, 0.8944272),
        Vec3::new(-0.23570226, -0.23570226, 0.94280905),
        Vec3::new(-0.4472136, 0.0, 0.8944272),
    ];
    for (n, m) in ns.iter().zip(mitsuba) {
        assert!((*n - m).length() < 1e-6, "{n} vs {m}");
    }
}

#[test]
fn a_vertex_of_only_degenerate_triangles_gets_no_normal() {
    let ps = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X * 2.0];
    let ns = angle_weighted_normals(&ps, &[[0, 1, 2], [0, 1, 3]]);
    assert!((ns[0] - Vec3::Z).length() < 1e-6);
    assert_eq!(ns[3], Vec3::ZERO);
}
