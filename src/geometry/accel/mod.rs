//! The bounding volume hierarchy over all primitives of all shapes: this module (here the
//! queries, in `build.rs` the build) is the only one that names `obvhs`.
//!
//! One binary BVH (obvhs' PLOC builder with reinsertion, `Bvh2`) indexes every primitive: the
//! whole of each sphere and disk and each triangle of each mesh, so analytic shapes and
//! triangles share one tree. The BVH does not own the shapes: the same slice must be passed to
//! [`Accel::build`] and to the queries.
//!
//! Instances ([`Instance`]: a group of shapes with its own `Accel`, placed by a transform) are
//! primitives of this tree too, by their world boxes; their leaf test carries the ray into the
//! group's object space and asks the group's BVH (see `instance.rs`).
//!
//! Robustness. obvhs's own `Ray::new` clamps tiny direction components to 1/ε before inverting,
//! which can cull boxes for rays almost parallel to an axis; rays here are built with exact
//! reciprocals instead (±f32::MAX for zero components, so no 0·∞ NaN). Each primitive box is
//! padded by 2⁻²⁰ of its largest coordinate so that rounding in the slab test cannot cull a
//! primitive whose own (watertight, conservative) test would report a hit.

mod alpha;
mod build;

pub use alpha::AlphaFn;
use build::PART;

use super::instance::Instance;
use super::ray::Ray;
use super::shape::{Intersection, PrimHit, Shape, Tri4, WatertightRay, intersect_triangle_with};
use super::wide::WideBvh;
use glam::Vec3;

/// Relative padding of primitive boxes.
const BOX_PAD: f32 = 1.0 / (1 << 20) as f32;

/// A (shape, primitive) pair, in BVH order; `shape` with [`INSTANCE`] set is instance
/// `shape & !INSTANCE`.
#[derive(Clone, Copy, Debug)]
struct PrimRef {
    shape: u32,
    prim: u32,
}

/// The flag of [`PrimRef::shape`] that marks an instance.
const INSTANCE: u32 = 1 << 31;

/// Primitives per [`Tri4`] block: leaves start at multiples of it, so that each block
/// belongs to one leaf and its triangles are tested together.
const BLOCK: usize = 4;

/// Most primitives in a leaf (two blocks).
const LEAF: u32 = 8;

/// A slot of the padded primitive order that holds nothing (leaves start at multiples of
/// [`BLOCK`]); no leaf covers it, so it is never tested.
const PAD: u32 = u32::MAX;

/// The primitive of a [`PAD`] slot: no shape, and not an instance.
const PAD_REF: PrimRef = PrimRef {
    shape: !INSTANCE,
    prim: 0,
};

/// A hit inside instance `i`, found along the object-space ray of scale `k`.
struct Closest {
    i: u32,
    pr: PrimRef,
    t_obj: f32,
    hit: PrimHit,
    ray: Ray,
    k: f32,
}

/// The BVH over a slice of shapes.
#[derive(Clone)]
pub struct Accel {
    /// Bounds (min, max) of the builder's root, m; `None` when there are no primitives. The
    /// builder's binary tree itself is dropped once collapsed (it is the largest allocation of
    /// a build: about 64 bytes per triangle).
    root_bounds: Option<(Vec3, Vec3)>,
    /// The builder's binary tree collapsed to 8- or 4-wide nodes (see `wide/`), which queries
    /// traverse.
    wide: WideBvh,
    /// Indexed by the BVH's primitive ids (already permuted, so no indirection at query time).
    /// Each leaf starts at a multiple of [`BLOCK`]; the slots after its primitives up to the
    /// next multiple are padding that no leaf covers.
    prims: Vec<PrimRef>,
    /// Triangle corners (m) by BVH primitive id, four ids per block (id / 4, lane id % 4),
    /// copied from the meshes so that a leaf's triangles are one contiguous record tested
    /// together (see `shape/triangle4.rs`); NaN lanes for padding and other primitives (mesh
    /// vertices are finite, so NaN marks "not a triangle").
    blocks: Vec<Tri4>,
    /// Primitives indexed (padding not counted).
    count: usize,
    /// The instances whose boxes are primitives here.
    instances: Vec<Instance>,
    /// Alpha tests by shape index (see [`Accel::with_alpha`]); empty when no shape has one.
    alpha: Vec<Option<AlphaFn>>,
}

impl std::fmt::Debug for Accel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Accel")
            .field("primitives", &self.count)
            .field("width", &self.wide.width())
            .field("nodes", &self.wide.node_count())
            .finish()
    }
}

impl Accel {
    /// Builds one BVH over all primitives of all `shapes` (fine with none). Primitives with
    /// non-finite or empty bounds are left out.
    pub fn build(shapes: &[Shape]) -> Accel {
        Self::build_with(shapes, PART, 8)
    }

    /// [`Accel::build`] over `shapes` and the `instances`' world boxes: the scene's top level.
    pub fn build_with_instances(shapes: &[Shape], instances: Vec<Instance>) -> Accel {
        Self::build_all(shapes, instances, PART, 8)
    }

    /// [`Accel::build`] with parts of `part` primitives when there are more than 2·`part` (see
    /// `build.rs`) and nodes at most `max_width` wide (8 where the CPU has AVX, else 4);
    /// exposed so that tests can exercise the parts and both widths on small scenes.
    #[doc(hidden)]
    pub fn build_with(shapes: &[Shape], part: usize, max_width: usize) -> Accel {
        Self::build_all(shapes, Vec::new(), part, max_width)
    }

    /// Number of primitives indexed.
    pub fn primitive_count(&self) -> usize {
        self.count
    }

    /// World bounds (min, max) of everything indexed, m (slightly padded), or `None` if empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        self.root_bounds
    }

    /// The closest hit of `ray` (unit `d`) with `t` in (0, `ray.t_max`), or `None`.
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray) -> Option<Intersection> {
        let inv_d = inv_direction(ray)?;
        let wt = WatertightRay::new(ray);
        // the closest hit so far: one of this tree's primitives, or (when `in_instance`) the
        // one recorded in `inst`; only closer hits are reported, so the last one wins
        let mut best: Option<(PrimRef, f32, PrimHit)> = None;
        let mut inst: Option<Closest> = None;
        let mut in_instance = false;
        let mut test = |id: usize, tri: Option<[Vec3; 3]>, t_max: f32| {
            if let Some((t, h)) = self.intersect_prim(shapes, id, tri, ray, &wt, t_max) {
                best = Some((self.prims[id], t, h));
                in_instance = false;
                return t;
            }
            let Some(i) = self.instance_at(id, tri) else {
                return f32::INFINITY;
            };
            match self.closest_in_instance(i, ray, t_max) {
                Some((t, c)) => {
                    inst = Some(c);
                    in_instance = true;
                    t
                }
                None => f32::INFINITY,
            }
        };
        self.wide.traverse(
            ray.o,
            inv_d,
            ray.t_max,
            false,
            #[inline(always)]
            |first, count, t_max| self.visit_leaf(first, count, ray, &wt, t_max, false, &mut test),
        );
        if in_instance {
            let Closest {
                i,
                pr,
                t_obj,
                hit,
                ray: oray,
                k,
            } = inst?;
            let inst = &self.instances[i as usize];
            let shape = inst.group.shapes.get(pr.shape as usize)?;
            let it = shape.interaction(pr.shape, pr.prim as usize, &oray, t_obj, &hit);
            return Some(inst.to_world(it, k));
        }
        let (pr, t, h) = best?;
        let shape = shapes.get(pr.shape as usize)?;
        Some(shape.interaction(pr.shape, pr.prim as usize, ray, t, &h))
    }

    /// The closest hit inside instance `i` along `ray` cut at `t_max`: its world distance and
    /// the record. Kept out of line so that the traversal's leaf closure stays small.
    #[inline(never)]
    fn closest_in_instance(&self, i: u32, ray: &Ray, t_max: f32) -> Option<(f32, Closest)> {
        let inst = &self.instances[i as usize];
        let (oray, k) = inst.to_object(&Ray { t_max, ..*ray })?;
        let (pr, t_obj, hit) = inst.group.accel.closest(&inst.group.shapes, &oray)?;
        Some((
            t_obj / k,
            Closest {
                i,
                pr,
                t_obj,
                hit,
                ray: oray,
                k,
            },
        ))
    }

    /// Whether instance `i` blocks `ray` before `t_max` (out of line, as above).
    #[inline(never)]
    fn instance_occludes(&self, i: u32, ray: &Ray, t_max: f32) -> bool {
        let inst = &self.instances[i as usize];
        match inst.to_object(&Ray { t_max, ..*ray }) {
            Some((oray, _)) => inst.group.accel.occluded(&inst.group.shapes, &oray),
            None => false,
        }
    }

    /// The closest hit among this tree's own primitives (not instances): (primitive, t, hit).
    fn closest(&self, shapes: &[Shape], ray: &Ray) -> Option<(PrimRef, f32, PrimHit)> {
        let inv_d = inv_direction(ray)?;
        let wt = WatertightRay::new(ray);
        let mut best = None;
        let mut test = |id: usize, tri: Option<[Vec3; 3]>, t_max: f32| match self
            .intersect_prim(shapes, id, tri, ray, &wt, t_max)
        {
            Some((t, h)) => {
                best = Some((self.prims[id], t, h));
                t
            }
            None => f32::INFINITY,
        };
        self.wide.traverse(
            ray.o,
            inv_d,
            ray.t_max,
            false,
            #[inline(always)]
            |first, count, t_max| self.visit_leaf(first, count, ray, &wt, t_max, false, &mut test),
        );
        best
    }

    /// Whether anything is hit with `t` in (0, `ray.t_max`) (shadow rays). Stops at the first
    /// hit found.
    pub fn occluded(&self, shapes: &[Shape], ray: &Ray) -> bool {
        let Some(inv_d) = inv_direction(ray) else {
            return false;
        };
        let wt = WatertightRay::new(ray);
        let t = self.wide.traverse(
            ray.o,
            inv_d,
            ray.t_max,
            true,
            #[inline(always)]
            |first, count, t_max| {
                // any hit will do: a distance inside the interval for a hit, else ∞
                // (instances through their group's tree)
                let mut test = |id: usize, tri: Option<[Vec3; 3]>, t_max: f32| {
                    if let Some((t, _)) = self.intersect_prim(shapes, id, tri, ray, &wt, t_max) {
                        return t;
                    }
                    match self.instance_at(id, tri) {
                        Some(i) if self.instance_occludes(i, ray, t_max) => {
                            0.5 * t_max.min(f32::MAX)
                        }
                        _ => f32::INFINITY,
                    }
                };
                self.visit_leaf(first, count, ray, &wt, t_max, true, &mut test)
            },
        );
        t < ray.t_max
    }

    /// Tests the primitives `first..first + count` of a leaf in order, each with
    /// `test(id, corners if a triangle, limit)` (a hit distance, or ∞), the limit lowered by
    /// each hit, after the block prefilter ([`Tri4::candidates`]) has set aside the triangles
    /// that cannot be hit below the limit at the leaf's start. Returns the smallest distance
    /// found below `t_max` (∞ if none); with `any_hit`, the first.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn visit_leaf(
        &self,
        first: usize,
        count: usize,
        ray: &Ray,
        wt: &WatertightRay,
        mut t_max: f32,
        any_hit: bool,
        test: &mut impl FnMut(usize, Option<[Vec3; 3]>, f32) -> f32,
    ) -> f32 {
        let mut found = f32::INFINITY;
        let end = first + count;
        let mut base = first - first % BLOCK;
        while base < end {
            let block = &self.blocks[base / BLOCK];
            // the lanes of this leaf: triangles the prefilter keeps, and other primitives
            let (lo, hi) = (first.max(base) - base, (end - base).min(BLOCK));
            let leaf_lanes = ((1u32 << hi) - 1) & !((1u32 << lo) - 1);
            let tris = block.triangle_lanes();
            let mut lanes = (block.candidates(ray, wt, t_max) | !tris) & leaf_lanes;
            while lanes != 0 {
                let l = lanes.trailing_zeros() as usize;
                lanes &= lanes - 1;
                let tri = (tris & (1 << l) != 0).then(|| block.corners(l));
                let t = test(base + l, tri, t_max);
                if t < t_max {
                    (t_max, found) = (t, t);
                    if any_hit {
                        return found;
                    }
                }
            }
            base += BLOCK;
        }
        found
    }

    /// The instance BVH primitive `id` stands for, if any (`tri`: its corners if it is a
    /// triangle, so a missed triangle is answered without reading `prims`).
    #[inline(always)]
    fn instance_at(&self, id: usize, tri: Option<[Vec3; 3]>) -> Option<u32> {
        if tri.is_some() {
            return None;
        }
        let shape = self.prims[id].shape;
        (shape & INSTANCE != 0).then_some(shape & !INSTANCE)
    }

    /// The test of BVH primitive `id`: a triangle from its copied corners `tri` with the ray's
    /// precomputed watertight setup `wt`, other shapes through [`Shape::intersect_primitive`].
    #[inline]
    fn intersect_prim(
        &self,
        shapes: &[Shape],
        id: usize,
        tri: Option<[Vec3; 3]>,
        ray: &Ray,
        wt: &WatertightRay,
        t_max: f32,
    ) -> Option<(f32, PrimHit)> {
        if !self.alpha.is_empty() {
            return self.intersect_prim_alpha(shapes, id, tri, ray, wt, t_max);
        }
        self.hit_prim(shapes, id, tri, ray, wt, t_max)
    }

    /// The primitive test itself, without alpha tests (shared by both paths).
    #[inline(always)]
    fn hit_prim(
        &self,
        shapes: &[Shape],
        id: usize,
        tri: Option<[Vec3; 3]>,
        ray: &Ray,
        wt: &WatertightRay,
        t_max: f32,
    ) -> Option<(f32, PrimHit)> {
        if let Some(tri) = tri {
            return intersect_triangle_with(tri, ray, wt, t_max)
                .map(|(t, b)| (t, PrimHit::Triangle { b }));
        }
        let pr = self.prims[id];
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
