//! The light tree: next-event estimation picks a light by its likely contribution at the
//! shading point, not by its power alone (Conty Estevez & Kulla 2018; pbrt-v4 §12.6.3,
//! `BVHLightSampler`).
//!
//! Lights with bounds ([`LightBounds`]: points, spots, luminaires, projectors, area lights) are
//! the leaves of a binary tree built once with the surface-area–orientation heuristic; the
//! others (lights at infinity, beams) are chosen beside it, each as likely as the whole tree
//! (pbrt-v4's rule: a sky's power through the scene's disk says little about how much of it a
//! point receives, and selection by it starved a spot beside a sky of samples). A pick first
//! chooses among those and the tree, then walks the tree from the root,
//! taking each child with probability proportional to its importance at the point, and
//! reuses the one uniform number throughout (rescaled in f64, so a deep walk leaves enough
//! bits for sampling the light). [`LightTree::pmf`] replays the walk along the light's stored
//! branch bits, with the same arithmetic, so the two agree exactly.
//!
//! Densities: `pmf` is a discrete probability over lights (unitless); a light whose subtree
//! has zero importance is never picked and has pmf 0 (the bounds are conservative: it cannot
//! contribute), except a lone light at the root, which is always picked.

use glam::Vec3;

use super::bounds::{Importance, LightBounds};

/// Buckets per axis for the split cost.
const BUCKETS: usize = 12;

#[derive(Clone, Debug)]
struct Node {
    bounds: Importance,
    /// Leaf: the light's index. Interior: the second child's node index (the first is next).
    child_or_light: u32,
    leaf: bool,
}

/// See the module doc.
#[derive(Clone, Debug, Default)]
pub struct LightTree {
    nodes: Vec<Node>,
    /// Per light: (branch bits from the root, least significant first, 1 = second child;
    /// depth) if it is in the tree.
    trail: Vec<Option<(u64, u32)>>,
    /// Lights outside the tree, each chosen with probability `p_other / others.len()`.
    others: Vec<u32>,
    /// Probability of choosing the other group.
    p_other: f64,
    /// Per light, the probability of a choice that ignores position: the groups as above,
    /// the tree's lights in proportion to power ([`LightTree::position_free`]).
    free: Vec<f64>,
    /// The light, when only one can be picked (no work per pick).
    single: Option<u32>,
}

impl LightTree {
    /// A tree over the lights with `bounds` (None: not boundable, chosen beside the tree, each
    /// with the tree's probability). Lights of zero `power` (W) are left out (never picked).
    pub fn build(bounds: &[Option<LightBounds>], power: &[f64]) -> LightTree {
        let n = bounds.len();
        let mut t = LightTree {
            trail: vec![None; n],
            ..Default::default()
        };
        let mut items: Vec<(u32, LightBounds)> = Vec::new();
        let mut p_tree = 0.0f64;
        for i in 0..n {
            let p = power[i].max(0.0);
            if !(p > 0.0) || !p.is_finite() {
                continue;
            }
            match bounds[i] {
                Some(b) if b.phi > 0.0 && b.lo.is_finite() && b.hi.is_finite() => {
                    items.push((i as u32, b));
                    p_tree += p;
                }
                _ => t.others.push(i as u32),
            }
        }
        let m = t.others.len() as f64;
        t.p_other = if items.is_empty() { 1.0 } else { m / (m + 1.0) };
        t.free = vec![0.0; n];
        for &(i, _) in &items {
            t.free[i as usize] = (1.0 - t.p_other) * power[i as usize] / p_tree;
        }
        for &i in &t.others {
            t.free[i as usize] = t.p_other / m;
        }
        t.single = match (items.as_slice(), t.others.as_slice()) {
            ([(i, _)], []) | ([], [i]) => Some(*i),
            _ => None,
        };
        if !items.is_empty() {
            t.build_node(&mut items, 0, 0);
        }
        t
    }

    /// Per light, a probability for choices that cannot depend on a shading point (the
    /// particle tracers' emission sampling, `bdpt`): the lights outside the tree and the tree
    /// as a whole equally likely, as in [`LightTree::pick`], and the tree's lights in
    /// proportion to power (W). Sums to 1 (or is all zero when no light emits).
    pub fn position_free(&self) -> &[f64] {
        &self.free
    }

    /// Appends the subtree over `items` (at `depth`, reached by `bits`); returns its bounds.
    fn build_node(
        &mut self,
        items: &mut [(u32, LightBounds)],
        bits: u64,
        depth: u32,
    ) -> LightBounds {
        let here = self.nodes.len();
        if items.len() == 1 {
            let (light, b) = items[0];
            self.nodes.push(Node {
                bounds: Importance::from(&b),
                child_or_light: light,
                leaf: true,
            });
            self.trail[light as usize] = Some((bits, depth));
            return b;
        }
        // past 32 levels, halve the list (ordered along its widest axis), so that a run of
        // lopsided splits cannot take a branch beyond the 64 bits of its trail
        let mid = if depth < 32 {
            split(items)
        } else {
            halve(items)
        };
        self.nodes.push(Node {
            bounds: Importance::from(&items[0].1),
            child_or_light: 0,
            leaf: false,
        });
        let (a, b) = items.split_at_mut(mid);
        let ba = self.build_node(a, bits, depth + 1);
        self.nodes[here].child_or_light = self.nodes.len() as u32;
        let bb = self.build_node(b, bits | (1 << depth), depth + 1);
        let u = ba.union(&bb);
        self.nodes[here].bounds = Importance::from(&u);
        u
    }

    /// A light for the shading point `p` (normal `n`, or zero), its probability, and `u`
    /// rescaled to a fresh uniform number in [0, 1). None if no light can contribute.
    #[inline]
    pub fn pick(&self, p: Vec3, n: Vec3, u: f32) -> Option<(usize, f32, f32)> {
        if let Some(i) = self.single {
            return Some((i as usize, 1.0, u));
        }
        if self.nodes.is_empty() && self.others.is_empty() {
            return None; // no light emits
        }
        let mut u = u as f64;
        if u < self.p_other {
            // uniform among the others: the integer part picks, the fraction is reused
            let x = u / self.p_other * self.others.len() as f64;
            let k = (x as usize).min(self.others.len() - 1);
            let i = self.others[k] as usize;
            return Some((i, self.free[i] as f32, unit(x - k as f64)));
        }
        u = (u - self.p_other) / (1.0 - self.p_other);
        let mut pmf = 1.0 - self.p_other;
        let mut node = 0usize;
        loop {
            let nd = &self.nodes[node];
            if nd.leaf {
                // a lone light is taken without its importance (as `pmf` does): where it cannot
                // contribute its sample is zero anyway, and a single-light scene pays nothing
                return Some((nd.child_or_light as usize, pmf as f32, unit(u)));
            }
            let (c0, c1) = (node + 1, nd.child_or_light as usize);
            let p0 = self.first_child_prob(c0, c1, p, n)?;
            if u < p0 {
                u /= p0;
                pmf *= p0;
                node = c0;
            } else {
                u = (u - p0) / (1.0 - p0);
                pmf *= 1.0 - p0;
                node = c1;
            }
        }
    }

    /// The probability that [`LightTree::pick`] at `p`, `n` returns `light`.
    pub fn pmf(&self, p: Vec3, n: Vec3, light: usize) -> f32 {
        if let Some(i) = self.single {
            return if i as usize == light { 1.0 } else { 0.0 };
        }
        let Some((bits, depth)) = self.trail[light] else {
            // one of the others (its position-free probability is its pick's), or none
            return self.free[light] as f32;
        };
        let mut pmf = 1.0 - self.p_other;
        let mut node = 0usize;
        for level in 0..depth {
            let nd = &self.nodes[node];
            let (c0, c1) = (node + 1, nd.child_or_light as usize);
            let Some(p0) = self.first_child_prob(c0, c1, p, n) else {
                return 0.0;
            };
            if bits >> level & 1 == 0 {
                pmf *= p0;
                node = c0;
            } else {
                pmf *= 1.0 - p0;
                node = c1;
            }
        }
        pmf as f32
    }

    /// Probability of descending into the first of two children; None if neither matters.
    #[inline]
    fn first_child_prob(&self, c0: usize, c1: usize, p: Vec3, n: Vec3) -> Option<f64> {
        let i0 = self.nodes[c0].bounds.at(p, n) as f64;
        let i1 = self.nodes[c1].bounds.at(p, n) as f64;
        let sum = i0 + i1;
        (sum > 0.0 && sum.is_finite()).then(|| i0 / sum)
    }
}

/// `u` as an f32 in [0, 1).
#[inline]
fn unit(u: f64) -> f32 {
    (u as f32).clamp(0.0, 1.0 - f32::EPSILON / 2.0)
}

/// Orders `items` and returns where to split them (0 < mid < len): the bucket boundary of least
/// cost over the three axes (pbrt-v4 `BVHLightSampler::buildBVH`: power × orientation measure ×
/// box surface area, scaled for boxes long on the split axis), or the middle of the list when
/// every centroid coincides.
fn split(items: &mut [(u32, LightBounds)]) -> usize {
    let (mut clo, mut chi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for (_, b) in items.iter() {
        clo = clo.min(b.centroid());
        chi = chi.max(b.centroid());
        lo = lo.min(b.lo);
        hi = hi.max(b.hi);
    }
    let diag = hi - lo;
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, first bucket on the right)
    for axis in 0..3 {
        let (a0, a1) = (clo[axis], chi[axis]);
        if !(a1 > a0) {
            continue;
        }
        let mut buckets: [Option<LightBounds>; BUCKETS] = [None; BUCKETS];
        for (_, b) in items.iter() {
            let k = bucket(b, axis, a0, a1);
            buckets[k] = Some(match buckets[k] {
                Some(x) => x.union(b),
                None => *b,
            });
        }
        let kr = diag.max_element() / diag[axis].max(1e-30);
        for cut in 1..BUCKETS {
            let join = |r: &[Option<LightBounds>]| {
                r.iter()
                    .flatten()
                    .fold(None, |acc: Option<LightBounds>, b| {
                        Some(acc.map_or(*b, |a| a.union(b)))
                    })
            };
            let (Some(l), Some(r)) = (join(&buckets[..cut]), join(&buckets[cut..])) else {
                continue;
            };
            let cost = kr * (cost(&l) + cost(&r));
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, cut));
            }
        }
    }
    let mid = match best {
        Some((_, axis, cut)) => {
            // the same bucketing as above decides the side
            let (a0, a1) = (clo[axis], chi[axis]);
            partition(items, |b| bucket(b, axis, a0, a1) < cut)
        }
        None => 0,
    };
    if mid == 0 || mid == items.len() {
        halve(items)
    } else {
        mid
    }
}

/// The bucket of `b`'s centroid along `axis`, whose centroids span [a0, a1] (a0 < a1).
#[inline]
fn bucket(b: &LightBounds, axis: usize, a0: f32, a1: f32) -> usize {
    (((b.centroid()[axis] - a0) / (a1 - a0) * BUCKETS as f32) as usize).min(BUCKETS - 1)
}

/// Orders `items` along the widest axis of their centroids and returns the middle.
fn halve(items: &mut [(u32, LightBounds)]) -> usize {
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for (_, b) in items.iter() {
        lo = lo.min(b.centroid());
        hi = hi.max(b.centroid());
    }
    let axis = (hi - lo).max_position();
    items.sort_by(|a, b| a.1.centroid()[axis].total_cmp(&b.1.centroid()[axis]));
    items.len() / 2
}

/// Moves the items for which `left` holds to the front; returns how many there are.
fn partition(items: &mut [(u32, LightBounds)], left: impl Fn(&LightBounds) -> bool) -> usize {
    let mut k = 0;
    for i in 0..items.len() {
        if left(&items[i].1) {
            items.swap(i, k);
            k += 1;
        }
    }
    k
}

/// The split heuristic's cost of a cluster: φ · M_Ω · surface area, with M_Ω the orientation
/// measure of its normal and emission cones (pbrt-v4 `EvaluateCost`; Conty Estevez & Kulla
/// eq. 1).
fn cost(b: &LightBounds) -> f32 {
    use std::f32::consts::PI;
    let theta_o = b.normals.cos_theta.clamp(-1.0, 1.0).acos();
    let theta_e = b.cos_e.clamp(-1.0, 1.0).acos();
    let theta_w = (theta_o + theta_e).min(PI);
    let (sin_o, cos_o) = theta_o.sin_cos();
    let m_omega = 2.0 * PI * (1.0 - cos_o)
        + PI / 2.0
            * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                + cos_o);
    let d = b.hi - b.lo;
    let area = 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
    // points have no area; a small floor keeps their clusters comparable
    b.phi * m_omega * area.max(1e-12)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(n: usize) -> (Vec<Option<LightBounds>>, Vec<f64>) {
        let b = (0..n)
            .map(|i| {
                Some(LightBounds::point(
                    Vec3::new(i as f32, 0.0, 0.0),
                    1.0 + i as f32,
                ))
            })
            .collect();
        let p = (0..n).map(|i| 1.0 + i as f64).collect();
        (b, p)
    }

    #[test]
    fn no_emitting_light_picks_nothing() {
        let t = LightTree::build(
            &[Some(LightBounds::point(Vec3::ZERO, 0.0)), None],
            &[0.0, 0.0],
        );
        assert_eq!(t.pick(Vec3::X, Vec3::ZERO, 0.3), None);
        assert_eq!(t.pmf(Vec3::X, Vec3::ZERO, 0), 0.0);
        assert_eq!(t.pmf(Vec3::X, Vec3::ZERO, 1), 0.0);
    }

    #[test]
    fn probabilities_sum_to_one_and_pick_agrees_with_pmf() {
        let (b, p) = row(37);
        let t = LightTree::build(&b, &p);
        for q in [Vec3::new(3.0, 1.0, 0.0), Vec3::new(-5.0, 0.2, 0.3)] {
            let total: f32 = (0..37).map(|i| t.pmf(q, Vec3::ZERO, i)).sum();
            assert!((total - 1.0).abs() < 1e-5, "Σ pmf = {total}");
            for k in 0..200 {
                let u = (k as f32 + 0.5) / 200.0;
                let (i, pr, ur) = t.pick(q, Vec3::ZERO, u).unwrap();
                assert_eq!(pr, t.pmf(q, Vec3::ZERO, i));
                assert!((0.0..1.0).contains(&ur));
            }
        }
    }
}
