//! Shapes: spheres, disks and triangle meshes, stored in world space.
//!
//! Each [`Shape`] is a set of *primitives* (1 for a sphere or disk, one per triangle for a mesh)
//! that the BVH indexes. Intersection is split in two steps so that the BVH stays cheap:
//! [`Shape::intersect_primitive`] returns the distance and a small [`PrimHit`] record, and
//! [`Shape::interaction`] turns the closest one into a full [`Intersection`] (point with error
//! bound, normals, uv) once traversal is over.
//!
//! Conventions: metres, radians; normals are unit; the geometric normal is the shape's outward or
//! front-face normal and is *not* flipped toward the ray. All intersection tests are two-sided.

mod bspline_curve;
mod clip;
mod curve;
mod cylinder;
mod disk;
mod loop_subdiv;
mod mesh;
mod obj;
mod obj_check;
mod ply;
mod ply_attributes;
mod ply_header;
mod ply_polygons;
mod sdf_cubic;
mod sdf_grid;
pub use ply::UV_NAMES;
pub use ply_attributes::MeshAttribute;
pub use ply_polygons::{PlyPolygons, read_ply_polygons};
mod serialized;
mod sphere;
mod triangle;
mod triangle4;

pub use bspline_curve::{BSplineCurve, PbrtCurve};
pub use clip::Clip;
pub use curve::LinearCurve;
pub use cylinder::Cylinder;
pub use disk::Disk;
pub use loop_subdiv::{Subdivided, loop_subdivide};
pub use mesh::Mesh;
pub use sdf_grid::SdfGrid;
pub use sphere::Sphere;
pub(crate) use triangle::{WatertightRay, intersect_triangle_with};
pub(crate) use triangle4::Tri4;

use super::ray::Ray;
use glam::{Vec2, Vec3};

/// A shape in world space. The closed set of shapes the renderer knows.
#[derive(Clone, Debug)]
pub enum Shape {
    Sphere(Sphere),
    Disk(Disk),
    Cylinder(Cylinder),
    Mesh(Mesh),
    /// Mitsuba's `linearcurve`: capsules along polylines.
    Curve(LinearCurve),
    /// Mitsuba's `bsplinecurve`: spheres swept along cubic B-splines.
    BSpline(BSplineCurve),
    /// Mitsuba's `sdfgrid`: the zero set of a trilinearly interpolated distance grid.
    SdfGrid(Box<SdfGrid>),
}

/// A point sampled on a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceSample {
    /// Position, m.
    pub p: Vec3,
    /// Absolute error bound of `p` per axis, m (for [`super::ray::spawn_ray_to`]).
    pub p_error: Vec3,
    /// Unit geometric normal, outward / front face.
    pub n: Vec3,
    /// Density of the sample with respect to surface area, m⁻².
    pub pdf_area: f32,
    /// Surface coordinates of the point, as [`Intersection::uv`] (for textured emitters).
    pub uv: Vec2,
}

/// A point sampled on a shape for a receiver at `p` ([`Shape::sample_solid_angle`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidAngleSample {
    /// The point, its normal and uv (`s.pdf_area` is the shape's area density, not this
    /// sample's).
    pub s: SurfaceSample,
    /// Unit direction from `p` to the point, and the distance, m.
    pub wi: Vec3,
    pub distance: f32,
    /// cos θ at the point: its normal · (−`wi`), signed (negative: seen from its back).
    pub cos_light: f32,
    /// Density of `wi` with respect to solid angle at `p`, sr⁻¹.
    pub pdf: f32,
}

/// What [`Shape::intersect_primitive`] remembers about a hit for [`Shape::interaction`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PrimHit {
    Sphere,
    Cylinder,
    /// The hit's position along a curve segment, in [0, 1].
    Curve {
        s: f32,
    },
    /// Local disk coordinates: the hit is `centre + a·u + b·v` with a² + b² ≤ 1.
    Disk {
        a: f32,
        b: f32,
    },
    /// Barycentric coordinates of the hit with respect to the triangle's vertices 0, 1, 2.
    Triangle {
        b: [f32; 3],
    },
}

/// A ray–surface intersection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intersection {
    /// Distance along the ray, m.
    pub t: f32,
    /// Hit point, m (on the surface, recomputed from surface coordinates, not `o + t·d`).
    pub p: Vec3,
    /// Absolute error bound of `p` per axis, m.
    pub p_error: Vec3,
    /// Unit geometric normal: the shape's outward / front-face normal, NOT flipped toward the ray.
    pub n_geom: Vec3,
    /// Unit shading normal: interpolated vertex normal if the mesh has normals, else `n_geom`.
    /// Always in the same hemisphere as `n_geom`.
    pub n_shading: Vec3,
    /// Surface parameterisation, see each shape.
    pub uv: Vec2,
    /// ∂p/∂u, m per unit u (world space; not normalised, possibly zero where the
    /// parameterisation degenerates). Its part perpendicular to the shading normal is the
    /// shading frame's first tangent, as Mitsuba 3 builds `sh_frame`, so anisotropic lobes and
    /// tangent-space normal maps are oriented as there.
    pub dpdu: Vec3,
    /// ∂p/∂v, m per unit v (world space, as `dpdu`), for bump maps.
    pub dpdv: Vec3,
    /// Index of the shape in the slice given to the BVH.
    pub shape: u32,
    /// Primitive within the shape (triangle index for meshes, 0 otherwise).
    pub prim: u32,
}

impl Intersection {
    /// The geometric normal flipped to the side of `dir`, for offsetting rays that leave there.
    #[inline]
    pub fn n_geom_toward(&self, dir: Vec3) -> Vec3 {
        crate::geometry::flip_toward(self.n_geom, dir)
    }
}

impl Shape {
    /// Surface area, m².
    pub fn area(&self) -> f32 {
        match self {
            Shape::Sphere(s) => s.area(),
            Shape::Disk(d) => d.area(),
            Shape::Cylinder(c) => c.area(),
            Shape::Mesh(m) => m.area(),
            Shape::Curve(c) => c.area(),
            // never an emitter (refused at build)
            Shape::BSpline(_) => 0.0,
            Shape::SdfGrid(_) => 0.0,
        }
    }

    /// A point uniformly distributed by area over the whole shape, from `u` in [0,1)² (meshes
    /// pick the triangle with `u.x` and reuse what is left of it, so a stratified set of `u`
    /// stays stratified over the surface). `pdf_area = 1 / area`, m⁻².
    pub fn sample_area(&self, u: Vec2) -> SurfaceSample {
        match self {
            Shape::Sphere(s) => s.sample_area(u),
            Shape::Disk(d) => d.sample_area(u),
            Shape::Cylinder(c) => c.sample_area(u),
            Shape::Mesh(m) => m.sample_area(u),
            Shape::Curve(c) => c.sample_area(u),
            Shape::BSpline(_) => SurfaceSample {
                p: Vec3::ZERO,
                p_error: Vec3::ZERO,
                n: Vec3::Z,
                pdf_area: 0.0,
                uv: u,
            },
            Shape::SdfGrid(g) => g.sample_area(u),
        }
    }

    /// A point of the shape seen from `p`, for next-event estimation, with the direction to it
    /// and its density with respect to solid angle at `p`, sr⁻¹ ([`SolidAngleSample`]). Spheres
    /// seen from outside sample the cone of directions they subtend (pbrt-v4 §6.2.4),
    /// so no sample falls on the far side; when only the side the normal points to matters
    /// (`one_sided`: a one-sided emitter), a cylinder seen from outside samples the arc of its
    /// wall that faces `p` ([`Cylinder`]'s `sample_facing`), which the rest of the wall hides;
    /// every other case samples by area ([`Shape::sample_area`]). Points sampled by area are
    /// converted, pdf_ω = pdf_A · r² / |cos θ_light| (Veach 1997, eq. 8.10). The density is the
    /// one [`Shape::pdf_solid_angle`] gives with the same `one_sided`. None for a degenerate
    /// sample (the point at `p`, a direction along the surface, a non-finite density).
    #[inline]
    pub fn sample_solid_angle(
        &self,
        p: Vec3,
        u: Vec2,
        one_sided: bool,
    ) -> Option<SolidAngleSample> {
        // the cone's density, or None: sampled by area, converted below
        let (s, cone_pdf) = match self {
            Shape::Sphere(sph) => match sph.sample_cone(p, u) {
                Some((s, pdf)) => (s, Some(pdf)),
                None => (self.sample_area(u), None),
            },
            Shape::Cylinder(c) if one_sided => (
                c.sample_facing(p, u).unwrap_or_else(|| c.sample_area(u)),
                None,
            ),
            _ => (self.sample_area(u), None),
        };
        let d = s.p - p;
        let r2 = d.length_squared();
        if r2 == 0.0 || s.pdf_area <= 0.0 {
            return None;
        }
        let distance = r2.sqrt();
        let wi = d / distance;
        let cos_light = s.n.dot(-wi);
        let pdf = cone_pdf.unwrap_or_else(|| s.pdf_area * r2 / cos_light.abs());
        (pdf.is_finite() && cos_light != 0.0).then_some(SolidAngleSample {
            s,
            wi,
            distance,
            cos_light,
            pdf,
        })
    }

    /// The solid-angle density, sr⁻¹, with which [`Shape::sample_solid_angle`] from `p` picks
    /// the direction `wi` (unit) toward the point `p_light` of normal `n_light` on this shape,
    /// `one_sided` as there. Zero for a direction along the surface, and for a point the
    /// sampler does not reach (a one-sided cylinder's wall facing away from `p`).
    pub fn pdf_solid_angle(
        &self,
        p: Vec3,
        wi: Vec3,
        p_light: Vec3,
        n_light: Vec3,
        one_sided: bool,
    ) -> f32 {
        let pdf_area = match self {
            Shape::Sphere(s) => {
                if let Some(pdf) = s.pdf_cone(p) {
                    return pdf;
                }
                1.0 / self.area()
            }
            Shape::Cylinder(c) if one_sided => match c.pdf_facing(p) {
                Some(_) if n_light.dot(wi) >= 0.0 => return 0.0,
                Some(pdf) => pdf,
                None => 1.0 / self.area(),
            },
            _ => 1.0 / self.area(),
        };
        let r2 = (p_light - p).length_squared();
        let cos_l = n_light.dot(-wi).abs();
        if cos_l == 0.0 || !(pdf_area > 0.0 && pdf_area.is_finite()) {
            return 0.0;
        }
        pdf_area * r2 / cos_l
    }

    /// Number of primitives the BVH indexes: 1 for spheres and disks, triangles for meshes.
    pub fn primitive_count(&self) -> usize {
        match self {
            Shape::Sphere(_) | Shape::Disk(_) | Shape::Cylinder(_) => 1,
            Shape::Mesh(m) => m.triangle_count(),
            Shape::Curve(c) => c.segment_count(),
            Shape::BSpline(c) => c.segment_count(),
            Shape::SdfGrid(g) => g.voxel_count(),
        }
    }

    /// World-space bounds (min, max) of primitive `i`, m. An out-of-range `i` gives an empty box
    /// (min = +∞, max = −∞).
    pub fn primitive_aabb(&self, i: usize) -> (Vec3, Vec3) {
        match self {
            Shape::Sphere(s) if i == 0 => s.aabb(),
            Shape::Disk(d) if i == 0 => d.aabb(),
            Shape::Cylinder(c) if i == 0 => c.aabb(),
            Shape::Mesh(m) if i < m.triangle_count() => m.triangle_aabb(i),
            Shape::Curve(c) if i < c.segment_count() => c.aabb(i),
            Shape::BSpline(c) if i < c.segment_count() => c.aabb(i),
            Shape::SdfGrid(g) if i < g.voxel_count() => g.aabb(i),
            _ => (Vec3::INFINITY, Vec3::NEG_INFINITY),
        }
    }

    /// Closest intersection of `ray` with primitive `i`, with `t` in (0, `ray.t_max`). `ray.d`
    /// must be unit. `None` for a miss or an out-of-range `i`. Tests are two-sided and
    /// conservative: a ray that starts on the surface (within its error bound) and leaves it
    /// does not hit it again.
    #[inline]
    pub fn intersect_primitive(&self, i: usize, ray: &Ray) -> Option<(f32, PrimHit)> {
        match self {
            Shape::Sphere(s) if i == 0 => s.intersect(ray).map(|t| (t, PrimHit::Sphere)),
            Shape::Disk(d) if i == 0 => d.intersect(ray),
            Shape::Cylinder(c) if i == 0 => c.intersect(ray).map(|t| (t, PrimHit::Cylinder)),
            Shape::Mesh(m) if i < m.triangle_count() => m.intersect_triangle(i, ray),
            Shape::Curve(c) if i < c.segment_count() => {
                c.intersect(i, ray).map(|(t, s)| (t, PrimHit::Curve { s }))
            }
            Shape::BSpline(c) if i < c.segment_count() => {
                c.intersect(i, ray).map(|(t, s)| (t, PrimHit::Curve { s }))
            }
            Shape::SdfGrid(g) if i < g.voxel_count() => {
                g.intersect(i, ray).map(|t| (t, PrimHit::Sphere))
            }
            _ => None,
        }
    }

    /// The full [`Intersection`] for a hit `(t, hit)` of `ray` on primitive `prim` found by
    /// [`Shape::intersect_primitive`]; `shape_id` is stored in the result. A `hit` of another shape kind is a caller bug; the
    /// result is then a valid point of this primitive but otherwise unspecified (no panic).
    pub fn interaction(
        &self,
        shape_id: u32,
        prim: usize,
        ray: &Ray,
        t: f32,
        hit: &PrimHit,
    ) -> Intersection {
        let mut it = match (self, hit) {
            (Shape::Sphere(s), _) => s.interaction(ray.at(t)),
            (Shape::Disk(d), PrimHit::Disk { a, b }) => d.interaction(*a, *b),
            (Shape::Disk(d), _) => {
                let (a, b) = d.local_coords(ray.at(t));
                d.interaction(a, b)
            }
            (Shape::Cylinder(c), _) => c.interaction(ray.at(t)),
            (Shape::Mesh(m), PrimHit::Triangle { b }) => m.interaction(prim, *b),
            (Shape::Mesh(m), _) => m.interaction(prim, [1.0 / 3.0; 3]),
            (Shape::Curve(c), PrimHit::Curve { s }) => c.interaction(prim, ray.at(t), *s),
            (Shape::Curve(c), _) => c.interaction(prim, ray.at(t), 0.5),
            (Shape::BSpline(c), PrimHit::Curve { s }) => c.interaction(prim, ray.at(t), *s, ray),
            (Shape::BSpline(c), _) => c.interaction(prim, ray.at(t), 0.5, ray),
            (Shape::SdfGrid(g), _) => g.interaction(prim, ray.at(t)),
        };
        it.t = t;
        it.shape = shape_id;
        it.prim = prim as u32;
        it
    }
}
