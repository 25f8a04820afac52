//! The slab tests of a wide node's boxes: SSE for 4 lanes (x86_64 baseline), AVX for 8 (only
//! reached from the AVX-compiled traversal), scalar lanes elsewhere; all with the same roundings.

use super::Node;

/// The slab test of a node's W boxes against the ray `o + t·d` (`inv` = 1/d, finite): bit l of
/// the mask is set when box l is entered at some t in [0, `t_max`), i.e. t_far ≥ t_near,
/// t_far ≥ 0 and t_near < `t_max`; also returns each box's entry distance t_near. Per axis
/// t0 = (lo − o)·inv and t1 = (hi − o)·inv, rounded as in obvhs's `Aabb::intersect_ray` (the
/// robustness argument in `accel.rs` rests on these roundings). No NaN can arise: boxes, origin
/// and reciprocals are finite. Every lane width computes the same roundings.
#[inline(always)]
pub(super) fn slab<const W: usize>(
    n: &Node<W>,
    o: [f32; 3],
    inv: [f32; 3],
    t_max: f32,
) -> (u32, [f32; W]) {
    let mut t_near = [0f32; W];
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::*;
        if W == 4 {
            // SSE2 is part of x86_64: four boxes per instruction.
            // SAFETY: SSE2 is always present on x86_64; each row is W = 4 f32 (unaligned loads).
            unsafe {
                let axis = |a: usize| {
                    let (oa, ia) = (_mm_set1_ps(o[a]), _mm_set1_ps(inv[a]));
                    let t0 = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(n.lo[a].as_ptr()), oa), ia);
                    let t1 = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(n.hi[a].as_ptr()), oa), ia);
                    (_mm_min_ps(t0, t1), _mm_max_ps(t0, t1))
                };
                let (nx, fx) = axis(0);
                let (ny, fy) = axis(1);
                let (nz, fz) = axis(2);
                let near = _mm_max_ps(_mm_max_ps(nx, ny), nz);
                let far = _mm_min_ps(_mm_min_ps(fx, fy), fz);
                let hit = _mm_and_ps(
                    _mm_and_ps(_mm_cmpge_ps(far, near), _mm_cmpge_ps(far, _mm_setzero_ps())),
                    _mm_cmplt_ps(near, _mm_set1_ps(t_max)),
                );
                _mm_storeu_ps(t_near.as_mut_ptr(), near);
                return (_mm_movemask_ps(hit) as u32, t_near);
            }
        }
        if W == 8 {
            // SAFETY: 8-wide nodes exist only when the CPU has AVX (WideBvh::collapse), and
            // this runs inside `traverse_avx`; each row is W = 8 f32 (unaligned loads).
            unsafe {
                let mask = slab8_avx(
                    n.lo.as_ptr().cast(),
                    n.hi.as_ptr().cast(),
                    o,
                    inv,
                    t_max,
                    t_near.as_mut_ptr(),
                );
                return (mask, t_near);
            }
        }
    }
    let mut mask = 0;
    for (l, tn) in t_near.iter_mut().enumerate() {
        let mut lo = f32::NEG_INFINITY;
        let mut hi = f32::INFINITY;
        for a in 0..3 {
            let t0 = (n.lo[a][l] - o[a]) * inv[a];
            let t1 = (n.hi[a][l] - o[a]) * inv[a];
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
        }
        *tn = lo;
        if hi >= lo && hi >= 0.0 && lo < t_max {
            mask |= 1 << l;
        }
    }
    (mask, t_near)
}

/// The 8-lane slab test on rows of 8 f32 (`lo`, `hi`: three rows each, by axis); writes the
/// entry distances to `t_near` (8 f32) and returns the hit mask.
///
/// # Safety
/// The CPU must have AVX; `lo` and `hi` must point to 24 readable f32, `t_near` to 8 writable.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn slab8_avx(
    lo: *const f32,
    hi: *const f32,
    o: [f32; 3],
    inv: [f32; 3],
    t_max: f32,
    t_near: *mut f32,
) -> u32 {
    use std::arch::x86_64::*;
    let axis = |a: usize| {
        let (oa, ia) = (_mm256_set1_ps(o[a]), _mm256_set1_ps(inv[a]));
        // SAFETY: rows a of lo and hi are within the 24 f32 the caller guarantees.
        let (l, h) = unsafe {
            (
                _mm256_loadu_ps(lo.add(8 * a)),
                _mm256_loadu_ps(hi.add(8 * a)),
            )
        };
        let t0 = _mm256_mul_ps(_mm256_sub_ps(l, oa), ia);
        let t1 = _mm256_mul_ps(_mm256_sub_ps(h, oa), ia);
        (_mm256_min_ps(t0, t1), _mm256_max_ps(t0, t1))
    };
    let (nx, fx) = axis(0);
    let (ny, fy) = axis(1);
    let (nz, fz) = axis(2);
    let near = _mm256_max_ps(_mm256_max_ps(nx, ny), nz);
    let far = _mm256_min_ps(_mm256_min_ps(fx, fy), fz);
    let hit = _mm256_and_ps(
        _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GE_OQ>(far, near),
            _mm256_cmp_ps::<_CMP_GE_OQ>(far, _mm256_setzero_ps()),
        ),
        _mm256_cmp_ps::<_CMP_LT_OQ>(near, _mm256_set1_ps(t_max)),
    );
    // SAFETY: the caller guarantees 8 writable f32.
    unsafe { _mm256_storeu_ps(t_near, near) };
    _mm256_movemask_ps(hit) as u32
}
