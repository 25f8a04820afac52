//! Meshes of Mitsuba's `rectangle` and `cube`, built from their object-space corners.

use super::*;

impl Mesh {
    /// The object-space square [−1, 1]² in the plane z = 0, normal +z (Mitsuba's `rectangle`),
    /// as 2 triangles, transformed. uv = ((x + 1)/2, (y + 1)/2).
    pub fn rectangle(transform: &Transform) -> Mesh {
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let positions = corners.map(|(x, y)| Vec3::new(x, y, 0.0)).to_vec();
        let uvs = corners
            .map(|(x, y)| Vec2::new((x + 1.0) / 2.0, (y + 1.0) / 2.0))
            .to_vec();
        Mesh::assemble(
            positions,
            None,
            Some(uvs),
            vec![[0, 1, 2], [0, 2, 3]],
            transform,
        )
    }

    /// The object-space cube [−1, 1]³ with outward faces, as 12 triangles (4 vertices per
    /// face), transformed. Each face's uv is Mitsuba 3's `cube`: u = (p·U + 1)/2, v = (p·V + 1)/2
    /// for the face's axes (U, V) below (measured in Mitsuba 3.9.1: its ∂p/∂u is 2U, ∂p/∂v 2V),
    /// so textures and anisotropic lobes on a cube read as there.
    pub fn cuboid(transform: &Transform) -> Mesh {
        // (outward normal, U, V) per face
        const FACES: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]),
            ([-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
            ([0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
            ([0.0, 0.0, -1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        let mut positions = Vec::with_capacity(24);
        let mut uvs = Vec::with_capacity(24);
        let mut indices = Vec::with_capacity(12);
        for (n, u, v) in FACES {
            let (n, a, b) = (Vec3::from(n), Vec3::from(u), Vec3::from(v));
            let base = positions.len() as u32;
            for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                positions.push(n + a * s + b * t);
                uvs.push(Vec2::new((s + 1.0) / 2.0, (t + 1.0) / 2.0));
            }
            // counter-clockwise seen from outside: the corners run along a × b
            if a.cross(b).dot(n) > 0.0 {
                indices.push([base, base + 1, base + 2]);
                indices.push([base, base + 2, base + 3]);
            } else {
                indices.push([base, base + 2, base + 1]);
                indices.push([base, base + 3, base + 2]);
            }
        }
        Mesh::assemble(positions, None, Some(uvs), indices, transform)
    }
}
