//! The bounding volume hierarchy over all primitives of all shapes. The only file that names
//! `obvhs`.
//!
//! One binary BVH (obvhs' PLOC builder with reinsertion, `Bvh2`) indexes every primitive: the
//! whole of each sphere and disk and each triangle of each mesh, so analytic shapes and
//! triangles share one tree. The BVH does not own the shapes: the same slice must be passed to
//! [`Accel::build`] and to the queries.
//!
//! Robustness. obvhs's own `Ray::new` clamps tiny direction components to 1/ε before inverting,
//! which can cull boxes for rays almost parallel to an axis; rays here are built with exact
//! reciprocals instead (±f32::MAX for zero components, so no 0·∞ NaN). Each primitive box is
//! padded by 2⁻²⁰ of its largest coordinate so that rounding in the slab test cannot cull a
//! primitive whose own (watertight, conservative) test would report a hit.

use super::bvh4::{BinaryNode, Bvh4};
use super::ray::Ray;
use super::shape::{Intersection, PrimHit, Shape, WatertightRay, intersect_triangle_with};
use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2;
use std::time::Duration;

/// Relative padding of primitive boxes.
const BOX_PAD: f32 = 1.0 / (1 << 20) as f32;

/// A (shape, primitive) pair, in BVH order.
#[derive(Clone, Copy, Debug)]
struct PrimRef {
    shape: u32,
    prim: u32,
    /// Whether the primitive is a triangle, whose corners are copied into [`Accel::tris`].
    triangle: bool,
}

/// The BVH over a slice of shapes.
#[derive(Clone)]
pub struct Accel {
    /// `None` when there are no primitives. Kept for its bounds; queries use `wide`.
    bvh: Option<Bvh2>,
    /// The same tree collapsed to 4-wide nodes (see `bvh4.rs`), which queries traverse.
    wide: Bvh4,
    /// Indexed by the BVH's primitive ids (already permuted, so no indirection at query time).
    prims: Vec<PrimRef>,
    /// Triangle corners (m) by BVH primitive id, copied from the meshes so that a leaf test reads
    /// one contiguous record instead of shape → index → position; zero for other primitives.
    tris: Vec<[Vec3; 3]>,
}

impl std::fmt::Debug for Accel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Accel")
            .field("primitives", &self.prims.len())
            .field("nodes", &self.bvh.as_ref().map_or(0, |b| b.nodes.len()))
            .finish()
    }
}

impl Accel {
    /// Builds one BVH over all primitives of all `shapes` (fine with none). Primitives with
    /// non-finite or empty bounds are left out.
    pub fn build(shapes: &[Shape]) -> Accel {
        let mut refs = Vec::new();
        let mut boxes = Vec::new();
        for (s, shape) in shapes.iter().enumerate() {
            for i in 0..shape.primitive_count() {
                let (lo, hi) = shape.primitive_aabb(i);
                if !(lo.is_finite() && hi.is_finite() && lo.cmple(hi).all()) {
                    continue;
                }
                let pad = lo.abs().max(hi.abs()).max_element() * BOX_PAD;
                boxes.push(Aabb::new((lo - pad).into(), (hi + pad).into()));
                refs.push(PrimRef {
                    shape: s as u32,
                    prim: i as u32,
                    triangle: matches!(shape, Shape::Mesh(_)),
                });
            }
        }
        if refs.is_empty() {
            return Accel {
                bvh: None,
                wide: Bvh4::default(),
                prims: Vec::new(),
                tris: Vec::new(),
            };
        }
        let bvh = build_bvh2(
            &boxes,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let prims: Vec<PrimRef> = bvh
            .primitive_indices
            .iter()
            .map(|&i| refs[i as usize])
            .collect();
        let tris = prims
            .iter()
            .map(|pr| match &shapes[pr.shape as usize] {
                Shape::Mesh(m) => m.vertices(pr.prim as usize),
                _ => [Vec3::ZERO; 3],
            })
            .collect();
        let binary: Vec<BinaryNode> = bvh
            .nodes
            .iter()
            .map(|n| BinaryNode {
                min: n.aabb().min.into(),
                max: n.aabb().max.into(),
                count: n.prim_count,
                first: n.first_index,
            })
            .collect();
        Accel {
            wide: Bvh4::collapse(&binary),
            bvh: Some(bvh),
            prims,
            tris,
        }
    }

    /// Number of primitives indexed.
    pub fn primitive_count(&self) -> usize {
        self.prims.len()
    }

    /// World bounds (min, max) of everything indexed, m (slightly padded), or `None` if empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let root = self.bvh.as_ref()?.nodes.first()?;
        let b = root.aabb();
        Some((b.min.into(), b.max.into()))
    }

    /// The closest hit of `ray` (unit `d`) with `t` in (0, `ray.t_max`), or `None`.
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray) -> Option<Intersection> {
        let inv_d = inv_direction(ray)?;
        let wt = WatertightRay::new(ray);
        let mut best: Option<(PrimRef, f32, PrimHit)> = None;
        self.wide
            .traverse(ray.o, inv_d, ray.t_max, false, |id, t_max| {
                match self.intersect_prim(shapes, id, ray, &wt, t_max) {
                    Some((t, h)) => {
                        best = Some((self.prims[id], t, h));
                        t
                    }
                    None => f32::INFINITY,
                }
            });
        let (pr, t, h) = best?;
        let shape = shapes.get(pr.shape as usize)?;
        Some(shape.interaction(pr.shape, pr.prim as usize, ray, t, &h))
    }

    /// Whether anything is hit with `t` in (0, `ray.t_max`) (shadow rays). Stops at the first
    /// hit found.
    pub fn occluded(&self, shapes: &[Shape], ray: &Ray) -> bool {
        let Some(inv_d) = inv_direction(ray) else {
            return false;
        };
        let wt = WatertightRay::new(ray);
        let t = self
            .wide
            .traverse(ray.o, inv_d, ray.t_max, true, |id, t_max| {
                self.intersect_prim(shapes, id, ray, &wt, t_max)
                    .map_or(f32::INFINITY, |(t, _)| t)
            });
        t < ray.t_max
    }

    /// The leaf test of BVH primitive `id`: triangles from their copied corners with the ray's
    /// precomputed watertight setup `wt`, other shapes through [`Shape::intersect_primitive`].
    #[inline]
    fn intersect_prim(
        &self,
        shapes: &[Shape],
        id: usize,
        ray: &Ray,
        wt: &WatertightRay,
        t_max: f32,
    ) -> Option<(f32, PrimHit)> {
        let pr = self.prims[id];
        if pr.triangle {
            return intersect_triangle_with(self.tris[id], ray, wt, t_max)
                .map(|(t, b)| (t, PrimHit::Triangle { b }));
        }
        let ray = Ray { t_max, ..*ray };
        shapes
            .get(pr.shape as usize)?
            .intersect_primitive(pr.prim as usize, &ray)
    }
}

/// Exact reciprocal directions for the slab test (±f32::MAX for zero components, so no 0·∞
/// NaN). `None` for rays that cannot hit anything (t_max ≤ 0 or NaN, non-finite origin or
/// direction).
#[inline]
fn inv_direction(ray: &Ray) -> Option<Vec3> {
    if !(ray.t_max > 0.0) || !ray.o.is_finite() || !ray.d.is_finite() {
        return None;
    }
    let recip = |x: f32| {
        let r = 1.0 / x;
        if r.is_finite() {
            r
        } else {
            f32::MAX.copysign(x)
        }
    };
    Some(Vec3::new(recip(ray.d.x), recip(ray.d.y), recip(ray.d.z)))
}
