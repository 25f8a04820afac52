//! Tests of `wide`.

use super::*;

/// A leaf test from a test of one primitive: each in turn, the limit lowered by hits.
fn each(mut f: impl FnMut(usize, f32) -> f32) -> impl FnMut(usize, usize, f32) -> f32 {
    move |first, count, mut t_max| {
        let mut best = f32::INFINITY;
        for id in first..first + count {
            let t = f(id, t_max);
            if t < t_max {
                (t_max, best) = (t, t);
            }
        }
        best
    }
}

/// A binary tree over unit boxes at x = 0, 2, 4, …: leaves of one primitive each.
fn chain(n: usize) -> Vec<BinaryNode> {
    // build a balanced tree recursively into a flat array (children adjacent)
    fn build(lo: usize, hi: usize, out: &mut Vec<BinaryNode>, at: usize) {
        let min = Vec3::new(2.0 * lo as f32, 0.0, 0.0);
        let max = Vec3::new(2.0 * (hi - 1) as f32 + 1.0, 1.0, 1.0);
        if hi - lo == 1 {
            out[at] = BinaryNode {
                min,
                max,
                count: 1,
                first: lo as u32,
            };
            return;
        }
        let first = out.len();
        out.push(out[at]);
        out.push(out[at]);
        out[at] = BinaryNode {
            min,
            max,
            count: 0,
            first: first as u32,
        };
        let mid = (lo + hi) / 2;
        build(lo, mid, out, first);
        build(mid, hi, out, first + 1);
    }
    let mut out = vec![
        BinaryNode {
            min: Vec3::ZERO,
            max: Vec3::ZERO,
            count: 0,
            first: 0
        };
        1
    ];
    build(0, n, &mut out, 0);
    out
}

#[test]
fn visits_every_leaf_on_the_ray_nearest_first() {
    for (n, width) in [1, 2, 3, 5, 17, 64, 300]
        .into_iter()
        .flat_map(|n| [(n, 4), (n, 8)])
    {
        let bvh = WideBvh::collapse(&chain(n), width);
        // a ray along +x through all boxes: the first box (id 0) is the closest hit
        let mut seen = Vec::new();
        let t = bvh.traverse(
            Vec3::new(-1.0, 0.5, 0.5),
            Vec3::new(1.0, f32::MAX, f32::MAX),
            f32::INFINITY,
            false,
            each(|id, _| {
                seen.push(id);
                1.0 + 2.0 * id as f32
            }),
        );
        assert_eq!(t, 1.0, "n = {n}");
        assert_eq!(seen.first(), Some(&0), "n = {n}: nearest leaf first");
        // a ray missing everything visits nothing
        let mut none = 0;
        bvh.traverse(
            Vec3::new(-1.0, 5.0, 0.5),
            Vec3::new(1.0, f32::MAX, f32::MAX),
            f32::INFINITY,
            false,
            each(|_, _| {
                none += 1;
                f32::INFINITY
            }),
        );
        assert_eq!(none, 0);
        // without hits, every leaf on the ray is visited exactly once
        let mut all = Vec::new();
        bvh.traverse(
            Vec3::new(-1.0, 0.5, 0.5),
            Vec3::new(1.0, f32::MAX, f32::MAX),
            f32::INFINITY,
            false,
            each(|id, _| {
                all.push(id);
                f32::INFINITY
            }),
        );
        all.sort_unstable();
        assert_eq!(all, (0..n).collect::<Vec<_>>());
    }
}
