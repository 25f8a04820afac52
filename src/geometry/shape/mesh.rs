//! Triangle meshes in world space, and the rectangle and cuboid built from them.

use super::triangle::{barycentric_point, intersect_triangle};
use super::{Intersection, PrimHit, SurfaceSample};
use crate::geometry::error::GeometryError;
use crate::geometry::float::gamma;
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use crate::sampling::{reuse, uniform_triangle};
use glam::{Vec2, Vec3};

mod primitives;

/// A triangle mesh, transformed to world space at construction.
///
/// Front faces: the geometric normal is `(p1 − p0) × (p2 − p0)` normalised (counter-clockwise
/// winding, as in OBJ). If the mesh has vertex normals, the geometric normal is instead flipped,
/// where needed, into the hemisphere of the interpolated vertex normal (pbrt's rule: normals
/// are more reliable than winding in exported files), so `n_geom` and `n_shading` always agree.
/// A mirroring transform reverses the stored winding so that front faces stay front faces.
///
/// uv: interpolated from the vertex uvs if present, else the barycentrics (b₁, b₂), i.e. (0, 0),
/// (1, 0), (0, 1) at vertices 0, 1, 2, as Mitsuba 3 parameterises a mesh without uvs.
/// A zero vertex normal means "none here": where the interpolated normal is zero the shading
/// normal falls back to the geometric one.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    indices: Vec<[u32; 3]>,
    /// For each kept triangle, its index among the triangles given to [`Mesh::new`] (which
    /// drops degenerate ones), for per-face data of the source file.
    source: Vec<u32>,
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
        let mut source = Vec::with_capacity(indices.len());
        let mut cumulative = Vec::with_capacity(indices.len());
        let mut total = 0.0f64;
        for (k, mut tri) in indices.into_iter().enumerate() {
            if flip {
                tri.swap(1, 2);
            }
            let [a, b, c] = tri.map(|i| positions[i as usize]);
            let area = 0.5 * (b - a).cross(c - a).length();
            if area > 0.0 {
                total += f64::from(area);
                cumulative.push(total);
                kept.push(tri);
                source.push(k as u32);
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
            source,
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

    /// The index among the triangles given to [`Mesh::new`] of kept triangle `i`.
    pub fn source_triangle(&self, i: usize) -> u32 {
        self.source[i]
    }

    /// Barycentric weights of triangle `i`'s stored corners (as [`Mesh::indices`]) at a point
    /// `p` on it, m: each in [0, 1] up to rounding, summing to 1.
    pub fn barycentrics(&self, i: usize, p: Vec3) -> [f32; 3] {
        let [a, b, c] = self.vertices(i);
        let n = (b - a).cross(c - a);
        let nn = n.length_squared();
        if nn == 0.0 {
            return [1.0, 0.0, 0.0];
        }
        let b1 = (p - a).cross(c - a).dot(n) / nn;
        let b2 = (b - a).cross(p - a).dot(n) / nn;
        [1.0 - b1 - b2, b1, b2]
    }

    /// Whether the mesh has vertex normals / uvs.
    pub fn has_normals(&self) -> bool {
        self.normals.is_some()
    }

    pub fn has_uvs(&self) -> bool {
        self.uvs.is_some()
    }

    /// Gives a mesh without vertex normals smooth ones computed from its faces
    /// (`angle_weighted_normals`, in world space, after the winding was oriented); a mesh
    /// with normals is unchanged. Mitsuba 3 does this for every mesh file without normals
    /// unless the shape says `face_normals` (src/render/mesh.cpp, `recompute_vertex_normals`).
    pub fn smooth_if_no_normals(&mut self) {
        if self.normals.is_none() {
            self.normals = Some(angle_weighted_normals(&self.positions, &self.indices));
        }
    }

    /// Drops the vertex normals: the mesh is shaded with its face normals (flat).
    pub fn drop_normals(&mut self) {
        self.normals = None;
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

    /// The uv of barycentrics `b` between the corners' uvs `t`.
    #[inline]
    fn blend_uv(t: [Vec2; 3], b: [f32; 3]) -> Vec2 {
        t[0] * b[0] + t[1] * b[1] + t[2] * b[2]
    }

    pub(crate) fn interaction(&self, i: usize, b: [f32; 3]) -> Intersection {
        let pv = self.vertices(i);
        let (p, p_error) = barycentric_point(pv, b);
        let (n_geom, n_shading) = self.normals_at(i, b);
        let (e1, e2) = (pv[1] - pv[0], pv[2] - pv[0]);
        let (uv, dpdu, dpdv) = match &self.uvs {
            Some(uvs) => {
                let [t0, t1, t2] = self.indices[i].map(|v| uvs[v as usize]);
                // ∂p/∂u, ∂p/∂v from the uv differences (pbrt-v4 §6.5.3): [d1; d2]·[∂p/∂u;
                // ∂p/∂v] = [e1; e2]; where uv is degenerate, e1 and e2 − e1
                let (d1, d2) = (t1 - t0, t2 - t0);
                let det = d1.x * d2.y - d1.y * d2.x;
                let dpdu = (e1 * d2.y - e2 * d1.y) / det;
                let dpdv = (e2 * d1.x - e1 * d2.x) / det;
                let (dpdu, dpdv) = if dpdu.is_finite() && dpdv.is_finite() {
                    (dpdu, dpdv)
                } else {
                    (e1, e2 - e1)
                };
                (Self::blend_uv([t0, t1, t2], b), dpdu, dpdv)
            }
            // Mitsuba's (b₁, b₂): ∂p/∂u = p₁ − p₀, ∂p/∂v = p₂ − p₀ (measured in Mitsuba 3.9.1)
            None => (Vec2::new(b[1], b[2]), e1, e2),
        };
        Intersection {
            t: 0.0,
            p,
            p_error,
            n_geom,
            n_shading,
            uv,
            dpdu,
            dpdv,
            shape: 0,
            prim: i as u32,
        }
    }

    /// Uniform by area: the triangle is chosen with probability area_i / area using `u.x`, whose
    /// position within the triangle's CDF interval, rescaled to [0, 1), and `u.y` place the
    /// point uniformly within it (sample reuse: no extra dimension, and stratification of `u`
    /// carries over to the surface). `pdf_area = 1 / area`.
    /// `cdf[i − 1]`, the CDF below triangle `i` (0 for the first).
    #[inline]
    fn cdf_start(&self, i: usize) -> f32 {
        if i == 0 { 0.0 } else { self.cdf[i - 1] }
    }

    pub(crate) fn sample_area(&self, u: Vec2) -> SurfaceSample {
        let i = self
            .cdf
            .partition_point(|&c| c <= u.x)
            .min(self.indices.len().saturating_sub(1));
        let u = Vec2::new(reuse(u.x, self.cdf_start(i), self.cdf[i]), u.y);
        let (b0, b1) = uniform_triangle(u);
        let b = [b0, b1, (1.0 - b0 - b1).max(0.0)];
        let (p, p_error) = barycentric_point(self.vertices(i), b);
        let uv = match &self.uvs {
            Some(uvs) => Self::blend_uv(self.indices[i].map(|v| uvs[v as usize]), b),
            None => Vec2::new(b[1], b[2]),
        };
        SurfaceSample {
            p,
            p_error: p_error + gamma(2) * p.abs(),
            n: self.normals_at(i, b).0,
            pdf_area: 1.0 / self.area,
            uv,
        }
    }
}

/// Unit vertex normals: at each vertex the sum of the unit normals (p1 − p0) × (p2 − p0) of the
/// triangles around it, each weighted by the triangle's angle at that vertex, normalised
/// (Thürmer & Wüthrich, "Computing vertex normals from polygonal facets", JGT 3(1), 1998; the
/// weighting of Mitsuba 3's `recompute_vertex_normals`). Zero-area triangles add nothing; a
/// vertex whose sum is zero gets the zero vector, which the mesh reads as "no normal here"
/// (the geometric normal is used).
pub fn angle_weighted_normals(positions: &[Vec3], indices: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; positions.len()];
    for tri in indices {
        let p = tri.map(|i| positions[i as usize]);
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        if n.length_squared() <= 0.0 || n.is_nan() {
            continue;
        }
        let n = n.normalize();
        for k in 0..3 {
            let a = p[(k + 1) % 3] - p[k];
            let b = p[(k + 2) % 3] - p[k];
            // the angle between the two edges at vertex k, robust for small and large angles
            let angle = a.cross(b).length().atan2(a.dot(b));
            sums[tri[k] as usize] += n * angle;
        }
    }
    sums.into_iter().map(Vec3::normalize_or_zero).collect()
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

#[cfg(test)]
mod tests;
