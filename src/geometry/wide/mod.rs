//! Wide BVHs: the binary tree from the builder (see `accel.rs`) collapsed so that each node
//! holds the boxes of up to W children side by side (structure of arrays), tested together:
//! W = 8 with AVX where the CPU has it (checked at run time), W = 4 with SSE otherwise (SSE2 is
//! part of x86_64); other targets run the same code with scalar lanes.
//!
//! Why. A binary tree visits more nodes than a wide one and tests one box per memory load; on
//! a large mesh traversal waits mostly on node loads, and an 8-wide tree has about two thirds
//! of a 4-wide tree's levels. Wald et al., "Getting rid of packets", 2008; Embree's BVH4/BVH8.
//!
//! Robustness is the binary tree's: the same (padded) boxes, the same slab test as obvhs's
//! `Aabb::intersect_ray` with exact reciprocals from the caller (±f32::MAX for zero components,
//! so no 0·∞ NaN), and a box is entered when its entry distance is below the closest hit so far.
//! Empty lanes are masked by their child code, never by a box that might compare true.
//!
//! Leaves are ranges `first..first + count` of primitive ids in the builder's order.

mod slab;

use std::mem::MaybeUninit;

use slab::slab;

use glam::Vec3;

/// A node of the binary input tree: `count == 0` for an inner node whose children are
/// `first` and `first + 1`; otherwise a leaf of primitives `first..first + count`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BinaryNode {
    pub min: Vec3,
    pub max: Vec3,
    pub count: u32,
    pub first: u32,
}

/// Child code of an unused lane.
const EMPTY: u32 = u32::MAX;

/// W children: boxes by axis and lane, and what each lane holds.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Node<const W: usize> {
    /// Box minima, `lo[axis][lane]`, m.
    lo: [[f32; W]; 3],
    /// Box maxima, `hi[axis][lane]`, m.
    hi: [[f32; W]; 3],
    /// Inner child: node index; leaf: first primitive id; [`EMPTY`] if unused.
    child: [u32; W],
    /// 0 for an inner child, else the leaf's primitive count.
    count: [u32; W],
}

impl<const W: usize> Node<W> {
    const UNUSED: Node<W> = Node {
        lo: [[0.0; W]; 3],
        hi: [[0.0; W]; 3],
        child: [EMPTY; W],
        count: [0; W],
    };
}

/// A traversal stack entry: (child code, leaf count or 0 for a node, entry distance in m).
type Entry = (u32, u32, f32);

/// Stack entries before traversal needs the heap; deeper trees (more than about 35 levels of
/// 8-wide nodes, only from degenerate input) use a `Vec` per query.
const STACK: usize = 256;

/// A W-wide tree. Empty when built from no nodes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Wide<const W: usize> {
    nodes: Vec<Node<W>>,
    /// Deepest chain of nodes, for the traversal stack size.
    depth: usize,
}

/// The tree queries traverse: 8-wide where the CPU has AVX, else 4-wide.
#[derive(Clone, Debug)]
pub(crate) enum WideBvh {
    Four(Wide<4>),
    Eight(Wide<8>),
}

impl Default for WideBvh {
    fn default() -> Self {
        WideBvh::Four(Wide::default())
    }
}

impl WideBvh {
    /// The widest tree this CPU can traverse (`max_width` 8 or 4 caps it, for tests).
    pub(crate) fn collapse(bin: &[BinaryNode], max_width: usize) -> WideBvh {
        if max_width >= 8 && avx() {
            WideBvh::Eight(Wide::collapse(bin))
        } else {
            WideBvh::Four(Wide::collapse(bin))
        }
    }

    /// Number of nodes.
    pub(crate) fn node_count(&self) -> usize {
        match self {
            WideBvh::Four(t) => t.nodes.len(),
            WideBvh::Eight(t) => t.nodes.len(),
        }
    }

    /// Lanes per node.
    pub(crate) fn width(&self) -> usize {
        match self {
            WideBvh::Four(_) => 4,
            WideBvh::Eight(_) => 8,
        }
    }

    /// See [`Wide::traverse`].
    #[inline]
    pub(crate) fn traverse(
        &self,
        o: Vec3,
        inv_d: Vec3,
        t_max: f32,
        any_hit: bool,
        leaf: impl FnMut(usize, usize, f32) -> f32,
    ) -> f32 {
        match self {
            WideBvh::Four(t) => t.traverse(o, inv_d, t_max, any_hit, leaf),
            WideBvh::Eight(t) => t.traverse(o, inv_d, t_max, any_hit, leaf),
        }
    }
}

/// Whether the CPU has AVX (cached by the standard library after the first call).
#[inline]
fn avx() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

impl<const W: usize> Wide<W> {
    /// Collapses a binary tree (root at index 0) into W-wide nodes: each node takes its two
    /// children and keeps opening the inner child of largest surface area until it has W.
    fn collapse(bin: &[BinaryNode]) -> Self {
        if bin.is_empty() {
            return Self::default();
        }
        let area = |n: &BinaryNode| {
            let e = (n.max - n.min).max(Vec3::ZERO);
            e.x * e.y + e.y * e.z + e.z * e.x
        };
        let mut nodes = vec![Node::<W>::UNUSED];
        let mut depth = 1;
        // (binary node, wide node to fill, its depth)
        let mut work = vec![(0usize, 0usize, 1usize)];
        while let Some((b, out, d)) = work.pop() {
            depth = depth.max(d);
            let root = &bin[b];
            let mut kids: Vec<usize> = if root.count > 0 {
                vec![b]
            } else {
                vec![root.first as usize, root.first as usize + 1]
            };
            while kids.len() < W {
                let open = kids
                    .iter()
                    .enumerate()
                    .filter(|(_, k)| bin[**k].count == 0)
                    .max_by(|a, b| area(&bin[*a.1]).total_cmp(&area(&bin[*b.1])))
                    .map(|(i, _)| i);
                let Some(i) = open else { break };
                let k = kids.swap_remove(i);
                kids.push(bin[k].first as usize);
                kids.push(bin[k].first as usize + 1);
            }
            for (lane, &k) in kids.iter().enumerate() {
                let n = bin[k];
                for a in 0..3 {
                    nodes[out].lo[a][lane] = n.min[a];
                    nodes[out].hi[a][lane] = n.max[a];
                }
                if n.count > 0 {
                    nodes[out].child[lane] = n.first;
                    nodes[out].count[lane] = n.count;
                } else {
                    let idx = nodes.len();
                    nodes.push(Node::UNUSED);
                    nodes[out].child[lane] = idx as u32;
                    work.push((k, idx, d + 1));
                }
            }
        }
        Self { nodes, depth }
    }

    /// Tests the boxes of node `code` below `t_max`: pushes the children hit but the nearest
    /// on `stack` (at `sp`), farthest first, prefetching the nodes among them, and returns the
    /// nearest (None if no box is hit).
    #[inline(always)]
    fn open(
        &self,
        code: u32,
        o: [f32; 3],
        inv: [f32; 3],
        t_max: f32,
        stack: &mut [MaybeUninit<Entry>],
        sp: &mut usize,
    ) -> Option<Entry> {
        let n = &self.nodes[code as usize];
        let (mask, t_near) = slab(n, o, inv, t_max);
        let mut hits = [(0f32, 0usize); W];
        let mut nh = 0;
        let mut m = mask;
        while m != 0 {
            let l = m.trailing_zeros() as usize;
            m &= m - 1;
            if n.child[l] != EMPTY {
                hits[nh] = (t_near[l], l);
                nh += 1;
            }
        }
        let hits = &mut hits[..nh];
        // farthest first, by insertion (at most W entries; the distances are not NaN, since
        // the reciprocals are finite and a NaN entry fails the tests above)
        for a in 1..nh {
            let mut b = a;
            while b > 0 && hits[b - 1].0 < hits[b].0 {
                hits.swap(b - 1, b);
                b -= 1;
            }
        }
        let (&(tn, l), rest) = hits.split_last()?;
        for &(tf, lf) in rest {
            if n.count[lf] == 0 {
                self.prefetch(n.child[lf]);
            }
            stack[*sp] = MaybeUninit::new((n.child[lf], n.count[lf], tf));
            *sp += 1;
        }
        Some((n.child[l], n.count[l], tn))
    }

    /// Asks the CPU to bring node `i` into the cache (a hint: no effect on results), for a
    /// sibling pushed on the stack, so that its loads overlap the descent into the nearest.
    #[inline(always)]
    fn prefetch(&self, i: u32) {
        #[cfg(target_arch = "x86_64")]
        if let Some(node) = self.nodes.get(i as usize) {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            let p = (node as *const Node<W>).cast::<i8>();
            // SAFETY: prefetching never faults, and the lines are inside the node.
            unsafe {
                for line in (0..size_of::<Node<W>>()).step_by(64) {
                    _mm_prefetch::<_MM_HINT_T0>(p.add(line));
                }
            }
        }
    }

    /// Visits the leaves whose boxes the ray `o + t·d` (with `inv_d` = 1/d, exact, ±f32::MAX
    /// for zero components) enters at t < the current limit, nearest box first. `leaf(first,
    /// count, t_max)` tests the leaf's primitives `first..first + count` and returns the
    /// smallest hit distance below `t_max` (∞ or anything not below it if none); a distance
    /// below the limit becomes the new limit. With `any_hit`, returns at the first hit.
    /// Returns the final limit (`t_max` if nothing was hit).
    #[inline]
    pub(crate) fn traverse(
        &self,
        o: Vec3,
        inv_d: Vec3,
        t_max: f32,
        any_hit: bool,
        leaf: impl FnMut(usize, usize, f32) -> f32,
    ) -> f32 {
        if self.nodes.is_empty() {
            return t_max;
        }
        let need = (W - 1) * self.depth + W;
        if need <= STACK {
            // Not initialised: a 3 KiB memset per ray cost more than the whole traversal.
            let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
            self.dispatch(&mut stack, o, inv_d, t_max, any_hit, leaf)
        } else {
            let mut stack = vec![MaybeUninit::<Entry>::uninit(); need];
            self.dispatch(&mut stack, o, inv_d, t_max, any_hit, leaf)
        }
    }

    /// The traversal compiled for AVX when the tree is 8-wide (only built when the CPU has
    /// it, see [`WideBvh::collapse`]), so that the 8-lane slab test inlines.
    #[inline(always)]
    fn dispatch(
        &self,
        stack: &mut [MaybeUninit<Entry>],
        o: Vec3,
        inv_d: Vec3,
        t_max: f32,
        any_hit: bool,
        leaf: impl FnMut(usize, usize, f32) -> f32,
    ) -> f32 {
        #[cfg(target_arch = "x86_64")]
        if W == 8 {
            // SAFETY: 8-wide trees exist only when `avx()` is true (WideBvh::collapse).
            return unsafe { traverse_avx(self, stack, o, inv_d, t_max, any_hit, leaf) };
        }
        self.traverse_with(stack, o, inv_d, t_max, any_hit, leaf)
    }

    #[inline(always)]
    fn traverse_with(
        &self,
        stack: &mut [MaybeUninit<Entry>],
        o: Vec3,
        inv_d: Vec3,
        mut t_max: f32,
        any_hit: bool,
        mut leaf: impl FnMut(usize, usize, f32) -> f32,
    ) -> f32 {
        // The entry visited now: the root, then the nearest child hit of each inner node
        // (taken without a trip through the stack), else the top of the stack. The order of
        // visits is that of pushing every child hit farthest first and popping.
        let mut cur: Entry = (0, 0, 0.0);
        let mut sp = 0;
        let (o, inv) = (o.to_array(), inv_d.to_array());
        loop {
            let (code, count, near) = cur;
            let next = if near >= t_max {
                None
            } else if count > 0 {
                let t = leaf(code as usize, count as usize, t_max);
                if t < t_max {
                    t_max = t;
                    if any_hit {
                        return t_max;
                    }
                }
                None
            } else {
                self.open(code, o, inv, t_max, stack, &mut sp)
            };
            cur = match next {
                Some(e) => e,
                None if sp == 0 => break,
                None => {
                    sp -= 1;
                    // SAFETY: entries 0..sp were all written (each push writes stack[sp]
                    // before sp grows), so stack[sp] is initialised.
                    unsafe { stack[sp].assume_init() }
                }
            };
        }
        t_max
    }
}

/// [`Wide::traverse_with`] compiled with AVX enabled.
///
/// # Safety
/// The CPU must have AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn traverse_avx<const W: usize>(
    t: &Wide<W>,
    stack: &mut [MaybeUninit<Entry>],
    o: Vec3,
    inv_d: Vec3,
    t_max: f32,
    any_hit: bool,
    leaf: impl FnMut(usize, usize, f32) -> f32,
) -> f32 {
    t.traverse_with(stack, o, inv_d, t_max, any_hit, leaf)
}

#[cfg(test)]
mod tests;
