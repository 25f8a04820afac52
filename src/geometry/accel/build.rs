//! Building the [`Accel`]: obvhs's binary tree (in Morton-ordered parts for large scenes), its
//! leaves padded to blocks of four, the triangle corners copied into [`Tri4`] blocks, and the
//! collapse into the wide tree that queries traverse.

use super::{Accel, BLOCK, BOX_PAD, INSTANCE, LEAF, PAD, PAD_REF, PrimRef};
use crate::geometry::instance::Instance;
use crate::geometry::shape::{Shape, Tri4};
use crate::geometry::wide::{BinaryNode, WideBvh};
use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use std::time::Duration;

impl Accel {
    /// The tree over `shapes` and the `instances`' world boxes (see [`Accel::build_with`]).
    pub(super) fn build_all(
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
                alpha: Vec::new(),
            };
        }
        let (mut binary, order) = build_binary(&boxes, part.max(1));
        drop(boxes);
        let order = pad_leaves(&mut binary, &order);
        let count = refs.len();
        let prims: Vec<PrimRef> = order
            .iter()
            .map(|&i| if i == PAD { PAD_REF } else { refs[i as usize] })
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
            alpha: Vec::new(),
        }
    }
}

/// Primitives per part of a large scene's build (see [`build_binary`]).
pub(super) const PART: usize = 1 << 19;

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
