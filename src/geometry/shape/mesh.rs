//! Triangle meshes in world space, and the rectangle and cuboid built from them.

use super::triangle::{barycentric_point, intersect_triangle};
use super::{Intersection, PrimHit, SurfaceSample};
use crate::geometry::error::GeometryError;
use crate::geometry::float::gamma;
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use crate::sampling::uniform_triangle;
use glam::{Vec2, Vec3};

/// A triangle mesh, transformed to world space at construction.
///
/// Front faces: the geometric normal is `(p1 − p0) × (p2 − p0)` normalised (counter-clockwise
/// winding, as in OBJ). If the mesh has vertex normals, the geometric normal is instead flipped,
/// where needed, into the hemisphere of the interpolated vertex normal (pbrt's rule: normals
/// are more reliable than winding in exported files), so `n_geom` and `n_shading` always agree.
/// A mirroring transform reverses the stored winding so that front faces stay front faces.
///
/// uv: interpolated from the vertex uvs if present, else (0,0), (1,0), (1,1) at vertices 0, 1, 2.
/// A zero vertex normal means "none here": where the interpolated normal is zero the shading
/// normal falls back to the geometric one.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    indices: Vec<[u32; 3]>,
    /// `cdf[i]` = area of triangles 0..=i divided by the total; the last entry is 1.
    cdf: Vec<f32>,
    area: f32,
}

impl Mesh {
    /// A mesh from object-space vertex data and triangles, transformed by `transform`.
    ///
    /// `normals` and `uvs`, when given, must have one entry per position. Errors for: no
    /// triangles, an index out of range, a non-finite position / normal / uv (also after
    /// transforming), mismatched attribute counts, or zero total area. Triangles of zero area
    /// (exactly collinear vertices after transforming) are dropped, so primitive indices count
    /// only the kept triangles.
    pub fn new(
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<Vec2>>,
        indices: Vec<[u32; 3]>,
        transform: &Transform,
    ) -> Result<Mesh, GeometryError> {
        if indices.is_empty() {
            return Err(GeometryError::EmptyMesh("has no triangles"));
        }
        check_all(
            "position",
            &positions,
            |p| p.is_finite(),
            |p| format!("{p}"),
        )?;
        if let Some(ns) = &normals {
            check_count("normals", ns.len(), positions.len())?;
            check_all("normal", ns, |n| n.is_finite(), |n| format!("{n}"))?;
        }
        if let Some(uv) = &uvs {
            check_count("uvs", uv.len(), positions.len())?;
            check_all("uv", uv, |t| t.is_finite(), |t| format!("{t}"))?;
        }
        for (triangle, tri) in indices.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= positions.len()) {
                return Err(GeometryError::IndexOutOfRange {
                    triangle,
                    index,
                    count: positions.len(),
                });
            }
        }
        let mesh = Mesh::assemble(positions, normals, uvs, indices, transform);
        check_all(
            "transformed position",
            &mesh.positions,
            |p| p.is_finite(),
            |p| format!("{p}"),
        )?;
        if mesh.indices.is_empty() {
            return Err(GeometryError::EmptyMesh(
                "has zero total area (every triangle is degenerate)",
            ));
        }
        if !mesh.area.is_finite() {
            return Err(GeometryError::NotFinite {
                what: "mesh area",
                value: mesh.area.to_string(),
            });
        }
        Ok(mesh)
    }

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

    /// The object-space cube [−1, 1]³ with outward faces, as 12 triangles (4 vertices per face,
    /// uv = the face's two other coordinates mapped to [0, 1]), transformed.
    pub fn cuboid(transform: &Transform) -> Mesh {
        let mut positions = Vec::with_capacity(24);
        let mut uvs = Vec::with_capacity(24);
        let mut indices = Vec::with_capacity(12);
        for axis in 0..3 {
            let (t1, t2) = (Vec3::AXES[(axis + 1) % 3], Vec3::AXES[(axis + 2) % 3]);
            for sign in [1.0f32, -1.0] {
                let n = Vec3::AXES[axis] * sign;
                // Counter-clockwise seen from outside: t1 × t2 = axis, so swap them on the
                // negative face.
                let (a, b) = if sign > 0.0 { (t1, t2) } else { (t2, t1) };
                let base = positions.len() as u32;
                for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                    positions.push(n + a * s + b * t);
                    uvs.push(Vec2::new((s + 1.0) / 2.0, (t + 1.0) / 2.0));
                }
                indices.push([base, base + 1, base + 2]);
                indices.push([base, base + 2, base + 3]);
            }
        }
        Mesh::assemble(positions, None, Some(uvs), indices, transform)
    }

    /// Transforms to world space, orients the winding, drops zero-area triangles and builds the
    /// area CDF. No validation (indices must be in range).
    fn assemble(
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<Vec2>>,
        indices: Vec<[u32; 3]>,
        transform: &Transform,
    ) -> Mesh {
        let positions: Vec<Vec3> = positions.iter().map(|&p| transform.point(p)).collect();
        let normals = normals.map(|ns| {
            ns.iter()
                .map(|&n| transform.normal(n).normalize_or_zero())
                .collect()
        });
        let flip = transform.swaps_handedness();
        let mut kept = Vec::with_capacity(indices.len());
        let mut cumulative = Vec::with_capacity(indices.len());
        let mut total = 0.0f64;
        for mut tri in indices {
            if flip {
                tri.swap(1, 2);
            }
            let [a, b, c] = tri.map(|i| positions[i as usize]);
            let area = 0.5 * (b - a).cross(c - a).length();
            if area > 0.0 {
                total += f64::from(area);
                cumulative.push(total);
                kept.push(tri);
            }
        }
        let mut cdf: Vec<f32> = cumulative.iter().map(|&c| (c / total) as f32).collect();
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        Mesh {
            positions,
            normals,
            uvs,
            indices: kept,
            cdf,
            area: total as f32,
        }
    }

    /// Total surface area, m².
    pub fn area(&self) -> f32 {
        self.area
    }

    /// Number of (kept) triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// World-space vertex positions, m.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Triangles as vertex indices (winding as stored, see the type's documentation).
    pub fn indices(&self) -> &[[u32; 3]] {
        &self.indices
    }

    /// Whether the mesh has vertex normals / uvs.
    pub fn has_normals(&self) -> bool {
        self.normals.is_some()
    }

    pub fn has_uvs(&self) -> bool {
        self.uvs.is_some()
    }

    #[inline]
    /// World-space corners of triangle `i`, m.
    pub(crate) fn vertices(&self, i: usize) -> [Vec3; 3] {
        self.indices[i].map(|v| self.positions[v as usize])
    }

    pub(crate) fn triangle_aabb(&self, i: usize) -> (Vec3, Vec3) {
        let [a, b, c] = self.vertices(i);
        (a.min(b).min(c), a.max(b).max(c))
    }

    #[inline]
    pub(crate) fn intersect_triangle(&self, i: usize, ray: &Ray) -> Option<(f32, PrimHit)> {
        intersect_triangle(self.vertices(i), ray).map(|(t, b)| (t, PrimHit::Triangle { b }))
    }

    /// Geometric and shading normals at barycentrics `b` on triangle `i`.
    fn normals_at(&self, i: usize, b: [f32; 3]) -> (Vec3, Vec3) {
        let [p0, p1, p2] = self.vertices(i);
        let mut ng = (p1 - p0).cross(p2 - p0).normalize_or(Vec3::Z);
        let Some(normals) = &self.normals else {
            return (ng, ng);
        };
        let [n0, n1, n2] = self.indices[i].map(|v| normals[v as usize]);
        let ns = (n0 * b[0] + n1 * b[1] + n2 * b[2]).normalize_or_zero();
        if ns == Vec3::ZERO {
            return (ng, ng);
        }
        if ng.dot(ns) < 0.0 {
            ng = -ng;
        }
        (ng, ns)
    }

    pub(crate) fn interaction(&self, i: usize, b: [f32; 3]) -> Intersection {
        let (p, p_error) = barycentric_point(self.vertices(i), b);
        let (n_geom, n_shading) = self.normals_at(i, b);
        let uv = match &self.uvs {
            Some(uvs) => {
                let [t0, t1, t2] = self.indices[i].map(|v| uvs[v as usize]);
                t0 * b[0] + t1 * b[1] + t2 * b[2]
            }
            None => Vec2::new(b[1] + b[2], b[2]),
        };
        Intersection {
            t: 0.0,
            p,
            p_error,
            n_geom,
            n_shading,
            uv,
            shape: 0,
            prim: i as u32,
        }
    }

    /// Uniform by area: the triangle is chosen with probability area_i / area using `u_extra`,
    /// the point uniformly within it using `u`. `pdf_area = 1 / area`.
    pub(crate) fn sample_area(&self, u: Vec2, u_extra: f32) -> SurfaceSample {
        let i = self
            .cdf
            .partition_point(|&c| c <= u_extra)
            .min(self.indices.len().saturating_sub(1));
        let (b0, b1) = uniform_triangle(u);
        let b = [b0, b1, (1.0 - b0 - b1).max(0.0)];
        let (p, p_error) = barycentric_point(self.vertices(i), b);
        SurfaceSample {
            p,
            p_error: p_error + gamma(2) * p.abs(),
            n: self.normals_at(i, b).0,
            pdf_area: 1.0 / self.area,
        }
    }
}

fn check_count(what: &'static str, got: usize, positions: usize) -> Result<(), GeometryError> {
    if got == positions {
        Ok(())
    } else {
        Err(GeometryError::AttributeCount {
            what,
            got,
            positions,
        })
    }
}

fn check_all<T>(
    what: &'static str,
    values: &[T],
    ok: impl Fn(&T) -> bool,
    show: impl Fn(&T) -> String,
) -> Result<(), GeometryError> {
    match values.iter().position(|v| !ok(v)) {
        None => Ok(()),
        Some(index) => Err(GeometryError::NonFiniteAttribute {
            what,
            index,
            value: show(&values[index]),
        }),
    }
}
