//! The bounding volume hierarchy over all primitives of all shapes. The only file that names
//! `obvhs`.
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

use super::instance::Instance;
use super::ray::Ray;
use super::shape::{Intersection, PrimHit, Shape, Tri4, WatertightRay, intersect_triangle_with};
use super::wide::{BinaryNode, WideBvh};
use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use std::time::Duration;

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
/// [`BLOCK`]).
const PAD: u32 = u32::MAX;

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
}

impl std::fmt::Debug for Accel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Accel")
            .field("primitives", &self.prims.len())
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
    /// [`build_binary`]) and nodes at most `max_width` wide (8 where the CPU has AVX, else 4);
    /// exposed so that tests can exercise the parts and both widths on small scenes.
    #[doc(hidden)]
    pub fn build_with(shapes: &[Shape], part: usize, max_width: usize) -> Accel {
        Self::build_all(shapes, Vec::new(), part, max_width)
    }

    fn build_all(
        shapes: &[Shape],
        instances: Vec<Instance>,
        part: usize,
        max_width: usize,
    ) -> Accel {
        let total: usize =
            shapes.iter().map(|s| s.primitive_count()).sum::<usize>() + instances.len();
        let mut refs = Vec::with_capacity(total);
        let mut boxes = Vec::with_capacity(total);
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
                });
            }
        }
        for (k, inst) in instances.iter().enumerate() {
            if let Some((lo, hi)) = inst.bounds()
                && lo.is_finite()
                && hi.is_finite()
            {
                boxes.push(Aabb::new(lo.into(), hi.into()));
                refs.push(PrimRef {
                    shape: INSTANCE | k as u32,
                    prim: 0,
                });
            }
        }
        if refs.is_empty() {
            return Accel {
                root_bounds: None,
                wide: WideBvh::default(),
                prims: Vec::new(),
                blocks: Vec::new(),
                count: 0,
                instances,
            };
        }
        let (mut binary, order) = build_binary(&boxes, part.max(1));
        drop(boxes);
        let order = pad_leaves(&mut binary, &order);
        let count = refs.len();
        let prims: Vec<PrimRef> = order
            .iter()
            .map(|&i| match i {
                PAD => PrimRef {
                    shape: PAD,
                    prim: 0,
                },
                _ => refs[i as usize],
            })
            .collect();
        drop((refs, order));
        let blocks = prims
            .chunks(BLOCK)
            .map(|c| {
                Tri4::new(std::array::from_fn(|l| {
                    let pr = c.get(l)?;
                    match shapes.get(pr.shape as usize) {
                        Some(Shape::Mesh(m)) => Some(m.vertices(pr.prim as usize)),
                        _ => None,
                    }
                }))
            })
            .collect();
        let root_bounds = binary.first().map(|n| (n.min, n.max));
        Accel {
            wide: WideBvh::collapse(&binary, max_width),
            root_bounds,
            prims,
            blocks,
            count,
            instances,
        }
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
        self.wide
            .traverse(ray.o, inv_d, ray.t_max, false, |first, count, t_max| {
                self.visit_leaf(first, count, ray, &wt, t_max, false, &mut test)
            });
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
        self.wide
            .traverse(ray.o, inv_d, ray.t_max, false, |first, count, t_max| {
                self.visit_leaf(first, count, ray, &wt, t_max, false, &mut test)
            });
        best
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
            .traverse(ray.o, inv_d, ray.t_max, true, |first, count, t_max| {
                let mut test = |id: usize, tri: Option<[Vec3; 3]>, t_max: f32| {
                    self.occluded_prim(shapes, id, tri, ray, &wt, t_max)
                };
                self.visit_leaf(first, count, ray, &wt, t_max, true, &mut test)
            });
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
                let tri = if tris & (1 << l) != 0 {
                    block.triangle(l)
                } else {
                    None
                };
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
        (shape & INSTANCE != 0 && shape != PAD).then_some(shape & !INSTANCE)
    }

    /// The any-hit test of BVH primitive `id` (`tri`: its corners if a triangle): a distance
    /// inside the interval for a hit, else ∞ (instances through their group's tree).
    #[inline(always)]
    fn occluded_prim(
        &self,
        shapes: &[Shape],
        id: usize,
        tri: Option<[Vec3; 3]>,
        ray: &Ray,
        wt: &WatertightRay,
        t_max: f32,
    ) -> f32 {
        if let Some((t, _)) = self.intersect_prim(shapes, id, tri, ray, wt, t_max) {
            return t;
        }
        if self
            .instance_at(id, tri)
            .is_some_and(|i| self.instance_occludes(i, ray, t_max))
        {
            // any hit will do: report one inside the interval
            0.5 * t_max.min(f32::MAX)
        } else {
            f32::INFINITY
        }
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

/// Primitives per part of a large scene's build (see [`build_binary`]).
const PART: usize = 1 << 19;

/// A binary tree over `boxes` (root at 0, inner children adjacent) and the primitive order its
/// leaves index (`order[k]` is an index into `boxes`).
///
/// Up to 2·[`PART`] primitives: one obvhs build (PLOC, reinsertion, leaf collapse). Beyond
/// that, obvhs's working set (about 200 bytes per primitive) would dominate peak memory: a
/// 10M-triangle mesh peaked at 2.7 GB. So the primitives are ordered along a Morton curve of
/// their centres, cut into parts of [`PART`], each part built alone, and a top tree built over
/// the parts' root boxes; each top leaf is replaced by its part's root. The parts are compact
/// cells of the curve, so the top levels are nearly what a single build would make; within a
/// part the tree is obvhs's own.
fn build_binary(boxes: &[Aabb], part: usize) -> (Vec<BinaryNode>, Vec<u32>) {
    // Leaves of at most eight primitives, in blocks of four whose triangles the prefilter tests
    // together (`shape/triangle4.rs`). With a scalar leaf test, leaves of two had cost less
    // than obvhs's default of eight (18 % fewer instructions on the height field); with the
    // prefilter, leaves of four took about 10 % less time than two on both benchmark scenes,
    // and eight 3–4 % less again on the height field (BENCHMARKS.md, issue 24).
    let params = BvhBuildParams {
        max_prims_per_leaf: LEAF,
        ..BvhBuildParams::medium_build()
    };
    let one = |boxes: &[Aabb], params: BvhBuildParams| {
        let bvh = build_bvh2(boxes, params, &mut Duration::default());
        let nodes: Vec<BinaryNode> = bvh
            .nodes
            .iter()
            .map(|n| BinaryNode {
                min: n.aabb().min.into(),
                max: n.aabb().max.into(),
                count: n.prim_count,
                first: n.first_index,
            })
            .collect();
        (nodes, bvh.primitive_indices)
    };
    if boxes.len() <= 2 * part {
        return one(boxes, params);
    }
    // Morton order of the box centres (21 bits per axis)
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for b in boxes {
        let c: Vec3 = b.center().into();
        (lo, hi) = (lo.min(c), hi.max(c));
    }
    let scale = ((1u32 << 21) - 1) as f32 / (hi - lo).max(Vec3::splat(f32::MIN_POSITIVE));
    let spread = |x: f32| {
        let mut v = (x.clamp(0.0, ((1u32 << 21) - 1) as f32) as u64) & 0x1f_ffff;
        v = (v | v << 32) & 0x1f_0000_0000_ffff;
        v = (v | v << 16) & 0x1f_0000_ff00_00ff;
        v = (v | v << 8) & 0x100f_00f0_0f00_f00f;
        v = (v | v << 4) & 0x10c3_0c30_c30c_30c3;
        (v | v << 2) & 0x1249_2492_4924_9249
    };
    let mut keyed: Vec<(u64, u32)> = boxes
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let c = (Vec3::from(b.center()) - lo) * scale;
            (spread(c.x) | spread(c.y) << 1 | spread(c.z) << 2, i as u32)
        })
        .collect();
    keyed.sort_unstable();
    let sorted: Vec<u32> = keyed.into_iter().map(|(_, i)| i).collect();

    // each part alone: its nodes appended after the top tree's, its primitives after the
    // previous parts'
    let mut parts = Vec::new();
    let mut order = Vec::with_capacity(boxes.len());
    for ids in sorted.chunks(part) {
        let sub: Vec<Aabb> = ids.iter().map(|&i| boxes[i as usize]).collect();
        let (nodes, local) = one(&sub, params);
        parts.push((nodes, order.len() as u32));
        order.extend(local.iter().map(|&k| ids[k as usize]));
    }
    let roots: Vec<Aabb> = parts
        .iter()
        .map(|(n, _)| Aabb::new(n[0].min.into(), n[0].max.into()))
        .collect();
    let top_params = BvhBuildParams {
        max_prims_per_leaf: 1,
        ..params
    };
    let (mut out, top_order) = one(&roots, top_params);
    for t in 0..out.len() {
        if out[t].count == 0 {
            continue;
        }
        // guaranteed by max_prims_per_leaf = 1 (a violation would drop parts silently)
        assert_eq!(out[t].count, 1, "top leaves hold one part");
        let (nodes, prim_base) = &parts[top_order[out[t].first as usize] as usize];
        let node_base = out.len() as u32;
        let shift = |n: &BinaryNode| {
            let base = if n.count == 0 { node_base } else { *prim_base };
            BinaryNode {
                first: n.first + base,
                ..*n
            }
        };
        // the part's root takes the top leaf's place; its other nodes keep their offsets
        // (the root's own slot, at node_base, stays unreferenced)
        let root = shift(&nodes[0]);
        out[t] = root;
        out.extend(nodes.iter().map(shift));
    }
    (out, order)
}

/// Gives each leaf reachable from the root of `binary` a run of slots starting at a multiple of
/// [`BLOCK`] (its primitives, then [`PAD`] up to the next multiple), so that each [`Tri4`]
/// block belongs to one leaf; rewrites the leaves' `first` to their slots and
/// returns the padded order (indices into the boxes, or [`PAD`]).
fn pad_leaves(binary: &mut [BinaryNode], order: &[u32]) -> Vec<u32> {
    let mut padded = Vec::with_capacity(order.len() + order.len() / 2);
    let mut stack = vec![0usize];
    while let Some(i) = stack.pop() {
        let n = binary[i];
        if n.count == 0 {
            stack.extend([n.first as usize, n.first as usize + 1]);
            continue;
        }
        let start = padded.len();
        padded.extend_from_slice(&order[n.first as usize..(n.first + n.count) as usize]);
        padded.resize(padded.len().next_multiple_of(BLOCK), PAD);
        binary[i].first = start as u32;
    }
    padded
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
