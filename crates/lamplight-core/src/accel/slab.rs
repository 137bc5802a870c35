//! The ray/box slab test both hierarchies use: a ray prepared once, then tested
//! against four boxes at a time, stored as `f32` structure of arrays.
//!
//! Per axis the ray meets a box's planes at `(plane - o) / d`; the entry is the
//! largest near distance, the exit the smallest far distance, and the box is
//! entered when `entry <= exit` (Kay and Kajiya's slabs).
//!
//! Conservative for `f64` rays against `f32` boxes: it may report a box the ray
//! misses, never miss one it enters. The origin is replaced by two `f32` points
//! bracketing it on every axis, `lower < o < upper`; minimum planes are measured
//! from `upper` and maximum planes from `lower`. For a positive direction that
//! makes the entry (minimum plane) no later and the exit (maximum plane) no earlier
//! than the true ones, and for a negative direction the same with the roles of the
//! planes swapped, so no index depends on the ray's signs. The entry/exit interval
//! is then widened by a few `f32` ulps for the rounding of the subtraction, the
//! product, the direction and its inverse (four half-ulps in all, against eight
//! in [`WIDEN`]). The strict bracket also covers a ray that
//! does not move along an axis and starts exactly on a box's face: its distances
//! on that axis are `+-1e30` scaled by a nonzero gap, never `0`, so it stays inside.
//!
//! `f32` rays (the ray-casting API) go through the same `f64` setup: converting
//! them is exact.

use glam::Vec4;

use crate::math::{max_abs, Vec3};

/// Relative widening of the entry/exit interval (a few f32 ulps).
pub(super) const WIDEN: f32 = 4.0 * f32::EPSILON;

/// A ray prepared for [`SlabRay::test`]. Scalars, splatted where a test uses
/// them: 40 bytes instead of 160 for the splatted vectors, which every batch
/// walk copies into its state once per ray (issue 24: a tenth of an incoherent
/// ray's instructions went to setting a walk up).
#[derive(Clone, Copy)]
pub(super) struct SlabRay {
    /// Per axis: an `f32` above the origin coordinate. Minimum planes are
    /// measured from it.
    upper_origin: [f32; 3],
    /// Per axis: an `f32` below the origin coordinate. Maximum planes are
    /// measured from it.
    lower_origin: [f32; 3],
    /// Per axis: inverse direction (finite: +-1e30 for zero components).
    inv_dir: [f32; 3],
    t_min: f32,
}

impl SlabRay {
    /// Prepares `origin + t dir`, `t >= t_min`, for box tests.
    #[inline(always)]
    pub(super) fn new(origin: Vec3, dir: Vec3, t_min: f64) -> SlabRay {
        // Bracket the origin: with pad = 2^-21 |o|_inf (+ a tiny absolute part for
        // o = 0), rounding o -+ pad to f32 moves it by at most half an f32 ulp,
        // 2^-24 |o|, less than pad, so lower < o < upper on every axis.
        let pad = max_abs(origin) * (1.0 / 2_097_152.0) + 1e-30;
        let lower = (origin - pad).as_vec3();
        let upper = (origin + pad).as_vec3();
        // One f32 division for the three axes: rounding the direction to f32 first
        // adds half an ulp to the inverse, inside WIDEN's allowance. 1/0 is an
        // infinity of the zero's sign; keep it finite so that no 0 * inf NaN can
        // arise in the box test.
        let inv = (Vec4::ONE / Vec4::new(dir.x as f32, dir.y as f32, dir.z as f32, 1.0)).clamp(Vec4::splat(-1e30), Vec4::splat(1e30));
        SlabRay {
            upper_origin: upper.to_array(),
            lower_origin: lower.to_array(),
            inv_dir: [inv.x, inv.y, inv.z],
            t_min: t_min.max(0.0) as f32,
        }
    }

    /// Entry distances of four boxes and the mask of those the ray enters before
    /// `t_max`. `row(r)` gives plane row `r` of the four boxes: minimum x, y, z,
    /// then maximum x, y, z. Lanes of unused slots must be masked by the caller:
    /// their planes are arbitrary here.
    #[inline(always)]
    pub(super) fn test(&self, row: impl Fn(usize) -> Vec4, t_max: f32) -> (Vec4, u32) {
        let axis = |a: usize| {
            let inv = Vec4::splat(self.inv_dir[a]);
            let to_min = (row(a) - Vec4::splat(self.upper_origin[a])) * inv;
            let to_max = (row(a + 3) - Vec4::splat(self.lower_origin[a])) * inv;
            (to_min.min(to_max), to_min.max(to_max))
        };
        let (near_x, far_x) = axis(0);
        let (near_y, far_y) = axis(1);
        let (near_z, far_z) = axis(2);
        let enter = near_x.max(near_y).max(near_z).max(Vec4::splat(self.t_min));
        let exit = far_x.min(far_y).min(far_z).min(Vec4::splat(t_max));
        let hit = (enter * (1.0 - WIDEN)).cmple(exit * (1.0 + WIDEN));
        (enter, hit.bitmask())
    }
}

/// [`SlabRay::test`] for eight boxes in one AVX pass: the same operations in the
/// same order per lane, so the entry distances and the mask are bit for bit
/// those of two four-box tests (`planes[r]` is row `r` of the eight boxes).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(super) fn test8_avx2(ray: &SlabRay, planes: &[[f32; 8]; 6], t_max: f32) -> ([f32; 8], u32) {
    use std::arch::x86_64::*;
    let splat = |v: f32| _mm256_set1_ps(v);
    // SAFETY: each row is eight f32s; unaligned loads.
    let row = |r: usize| unsafe { _mm256_loadu_ps(planes[r].as_ptr()) };
    let axis = |a: usize| {
        let inv = splat(ray.inv_dir[a]);
        let to_min = _mm256_mul_ps(_mm256_sub_ps(row(a), splat(ray.upper_origin[a])), inv);
        let to_max = _mm256_mul_ps(_mm256_sub_ps(row(a + 3), splat(ray.lower_origin[a])), inv);
        (_mm256_min_ps(to_min, to_max), _mm256_max_ps(to_min, to_max))
    };
    let (near_x, far_x) = axis(0);
    let (near_y, far_y) = axis(1);
    let (near_z, far_z) = axis(2);
    let enter = _mm256_max_ps(_mm256_max_ps(_mm256_max_ps(near_x, near_y), near_z), splat(ray.t_min));
    let exit = _mm256_min_ps(_mm256_min_ps(_mm256_min_ps(far_x, far_y), far_z), _mm256_set1_ps(t_max));
    let below = _mm256_mul_ps(enter, _mm256_set1_ps(1.0 - WIDEN));
    let above = _mm256_mul_ps(exit, _mm256_set1_ps(1.0 + WIDEN));
    let hit = _mm256_cmp_ps::<_CMP_LE_OS>(below, above);
    let mut out = [0.0f32; 8];
    // SAFETY: `out` holds eight f32s; unaligned store.
    unsafe { _mm256_storeu_ps(out.as_mut_ptr(), enter) };
    (out, _mm256_movemask_ps(hit) as u32)
}

/// Eight rays prepared for testing one box at a time, a ray per AVX lane: the
/// packet walk of camera rays (`mesh_packet.rs`). Lane `i` holds ray `i`'s
/// [`SlabRay`] values, so [`SlabPacket::test_box`] does per lane exactly what
/// [`test8_avx2`] does per box: the same operations on the same values in the same
/// order, and the same bits.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
pub(super) struct SlabPacket {
    upper_origin: [std::arch::x86_64::__m256; 3],
    lower_origin: [std::arch::x86_64::__m256; 3],
    inv_dir: [std::arch::x86_64::__m256; 3],
    t_min: std::arch::x86_64::__m256,
}

#[cfg(target_arch = "x86_64")]
impl SlabPacket {
    /// The eight rays' values, lane by lane.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(super) fn new(rays: &[SlabRay; 8]) -> SlabPacket {
        use std::arch::x86_64::*;
        let lanes = |f: &dyn Fn(&SlabRay) -> f32| {
            let v = rays.each_ref().map(f);
            // SAFETY: eight f32s; unaligned load.
            unsafe { _mm256_loadu_ps(v.as_ptr()) }
        };
        let axes = |f: &dyn Fn(&SlabRay, usize) -> f32| [0, 1, 2].map(|a| lanes(&|r| f(r, a)));
        SlabPacket {
            upper_origin: axes(&|r, a| r.upper_origin[a]),
            lower_origin: axes(&|r, a| r.lower_origin[a]),
            inv_dir: axes(&|r, a| r.inv_dir[a]),
            t_min: lanes(&|r| r.t_min),
        }
    }

    /// Box `slot` of `planes` against the eight rays, each with its own `t_max`
    /// lane: the entry distances and the mask of the rays that enter it.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(super) fn test_box(
        &self,
        planes: &[[f32; 8]; 6],
        slot: usize,
        t_max: std::arch::x86_64::__m256,
    ) -> (std::arch::x86_64::__m256, u32) {
        use std::arch::x86_64::*;
        let axis = |a: usize| {
            let inv = self.inv_dir[a];
            let to_min = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(planes[a][slot]), self.upper_origin[a]), inv);
            let to_max = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(planes[a + 3][slot]), self.lower_origin[a]), inv);
            (_mm256_min_ps(to_min, to_max), _mm256_max_ps(to_min, to_max))
        };
        let (near_x, far_x) = axis(0);
        let (near_y, far_y) = axis(1);
        let (near_z, far_z) = axis(2);
        let enter = _mm256_max_ps(_mm256_max_ps(_mm256_max_ps(near_x, near_y), near_z), self.t_min);
        let exit = _mm256_min_ps(_mm256_min_ps(_mm256_min_ps(far_x, far_y), far_z), t_max);
        let below = _mm256_mul_ps(enter, _mm256_set1_ps(1.0 - WIDEN));
        let above = _mm256_mul_ps(exit, _mm256_set1_ps(1.0 + WIDEN));
        (enter, _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(below, above)) as u32)
    }
}

/// The entry distances of eight boxes (`planes[r]` is row `r` of the eight) and
/// the mask of those entered before `t_max`: one AVX test when `AVX2` (set only
/// on CPUs that have it, by a caller compiled for it), else two four-box tests,
/// with the same bits either way. Lanes of unused slots must be masked by the caller.
#[inline(always)]
pub(super) fn test8<const AVX2: bool>(ray: &SlabRay, planes: &[[f32; 8]; 6], t_max: f32) -> ([f32; 8], u32) {
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: `AVX2` is set only on CPUs that have it.
        return unsafe { test8_avx2(ray, planes, t_max) };
    }
    let half = |h: usize| ray.test(|r| Vec4::from_slice(&planes[r][4 * h..4 * h + 4]), t_max);
    let (lo, lo_mask) = half(0);
    let (hi, hi_mask) = half(1);
    let mut enter = [0.0; 8];
    enter[..4].copy_from_slice(&lo.to_array());
    enter[4..].copy_from_slice(&hi.to_array());
    (enter, lo_mask | hi_mask << 4)
}

/// Whether this CPU runs the eight-box test in one AVX pass (detected once per
/// process by the standard library, then a load and a test).
#[inline(always)]
pub(super) fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The children whose bits are set in `mask`, as `(entry distance, slot)` sorted
/// farthest first into `order[..n]`, and their number `n`: traversal pushes all
/// but the last and continues with the last, the nearest. Insertion sort: a node
/// has at most eight.
///
/// `order` is the walk's own, reused from node to node. Returned by value, the
/// array was copied out with 32-byte loads right after the sort's 8-byte stores,
/// which the core cannot forward: a stall at every node with two or more
/// children entered (issue 24, 4 % of the bunny's incoherent walk).
#[inline(always)]
pub(super) fn farthest_first<const N: usize>(enter: &[f32; N], mut mask: u32, order: &mut [(f32, u32); N]) -> usize {
    let mut n = 0;
    while mask != 0 {
        let slot = mask.trailing_zeros();
        mask &= mask - 1;
        let t = enter[slot as usize];
        let mut j = n;
        while j > 0 && order[j - 1].0 < t {
            order[j] = order[j - 1];
            j -= 1;
        }
        order[j] = (t, slot);
        n += 1;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(min: [f32; 3], max: [f32; 3]) -> impl Fn(usize) -> Vec4 {
        move |r| Vec4::splat(if r < 3 { min[r] } else { max[r - 3] })
    }

    #[test]
    fn entered_children_come_farthest_first() {
        let mut order = [(-1.0, 99); 8];
        let n = farthest_first(&[3.0, 1.0, 7.0, 2.0, 0.5, 9.0, 4.0, 6.0], 0b1010_1101, &mut order);
        assert_eq!(n, 5);
        assert_eq!(order[..n], [(9.0, 5), (7.0, 2), (6.0, 7), (3.0, 0), (2.0, 3)]);
    }

    #[test]
    fn a_ray_along_a_face_is_inside() {
        // The ray lies in the plane x = 1, the box's maximum x: it touches the box.
        let ray = SlabRay::new(Vec3::new(1.0, 0.5, -5.0), Vec3::Z, 0.0);
        let (_, mask) = ray.test(rows([0.0; 3], [1.0; 3]), f32::INFINITY);
        assert_eq!(mask, 0b1111);
        // Along the minimum face x = 0, travelling the other way.
        let ray = SlabRay::new(Vec3::new(0.0, 0.5, 5.0), -Vec3::Z, 0.0);
        assert_eq!(ray.test(rows([0.0; 3], [1.0; 3]), f32::INFINITY).1, 0b1111);
        // Just outside the face: missed.
        let ray = SlabRay::new(Vec3::new(1.001, 0.5, -5.0), Vec3::Z, 0.0);
        assert_eq!(ray.test(rows([0.0; 3], [1.0; 3]), f32::INFINITY).1, 0);
    }

    #[test]
    fn entry_distances_and_t_limits() {
        let ray = SlabRay::new(Vec3::new(0.5, 0.5, -2.0), Vec3::Z, 0.0);
        let (enter, mask) = ray.test(rows([0.0; 3], [1.0; 3]), f32::INFINITY);
        assert_eq!(mask, 0b1111);
        assert!((enter.x - 2.0).abs() < 1e-5);
        // The box lies beyond t_max = 1.5, or before t_min = 3.5: not entered.
        assert_eq!(ray.test(rows([0.0; 3], [1.0; 3]), 1.5).1, 0);
        let late = SlabRay::new(Vec3::new(0.5, 0.5, -2.0), Vec3::Z, 3.5);
        assert_eq!(late.test(rows([0.0; 3], [1.0; 3]), f32::INFINITY).1, 0);
        // Negative directions see the same box from the other side.
        let back = SlabRay::new(Vec3::new(0.5, 0.5, 3.0), -Vec3::Z, 0.0);
        let (enter, mask) = back.test(rows([0.0; 3], [1.0; 3]), f32::INFINITY);
        assert_eq!(mask, 0b1111);
        assert!((enter.x - 2.0).abs() < 1e-5);
    }

    /// The packet test of one box against eight rays gives, lane by lane, the
    /// bits of each ray's own eight-box test (random rays and boxes as below).
    #[cfg(target_arch = "x86_64")]
    #[test]
    #[allow(clippy::needless_range_loop)] // slots index two rows of the planes at once
    fn one_box_against_eight_rays_is_each_rays_own_test_bit_for_bit() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("skipped: this CPU has no AVX2");
            return;
        }
        let mut rng = crate::sampling::Rng::for_sample(4, 0, 0);
        let mut value = |scale: f64| ((rng.uniform() - 0.5) * scale) as f32;
        let mut entered = 0;
        for case in 0..500 {
            let mut planes = [[0.0f32; 8]; 6];
            for slot in 0..8 {
                for axis in 0..3 {
                    let (a, b) = (value(8.0), value(8.0));
                    (planes[axis][slot], planes[axis + 3][slot]) = (a.min(b), a.max(b));
                }
            }
            let rays: [SlabRay; 8] = std::array::from_fn(|lane| {
                let mut dir = Vec3::new(value(2.0).into(), value(2.0).into(), value(2.0).into());
                if (case + lane) % 3 == 0 {
                    dir[lane % 3] = 0.0;
                }
                let origin = Vec3::new(value(12.0).into(), value(12.0).into(), value(12.0).into());
                SlabRay::new(origin, dir, if lane == 5 { 0.5 } else { 0.0 })
            });
            let t_max: [f32; 8] = std::array::from_fn(|lane| if (case + lane) % 2 == 0 { f32::INFINITY } else { value(10.0).abs() });
            // SAFETY: the CPU has AVX2 (checked above).
            unsafe {
                use std::arch::x86_64::*;
                let packet = SlabPacket::new(&rays);
                let limits = _mm256_loadu_ps(t_max.as_ptr());
                for slot in 0..8 {
                    let (enter, mask) = packet.test_box(&planes, slot, limits);
                    let mut lanes = [0.0f32; 8];
                    _mm256_storeu_ps(lanes.as_mut_ptr(), enter);
                    for lane in 0..8 {
                        let (want, want_mask) = test8_avx2(&rays[lane], &planes, t_max[lane]);
                        assert_eq!(lanes[lane].to_bits(), want[slot].to_bits(), "case {case} slot {slot} lane {lane}");
                        assert_eq!(mask >> lane & 1, want_mask >> slot & 1, "case {case} slot {slot} lane {lane}");
                        entered += mask >> lane & 1;
                    }
                }
            }
        }
        assert!(entered > 1000 && entered < 31000, "both entered and missed boxes: {entered}");
    }

    /// The AVX test of eight boxes gives the bits of two four-box tests: random
    /// boxes (some empty, as unused slots are), rays with zero direction
    /// components, origins inside and outside, finite and infinite `t_max`.
    #[cfg(target_arch = "x86_64")]
    #[test]
    #[allow(clippy::needless_range_loop)] // slots index two rows of the planes at once
    fn eight_boxes_at_once_are_two_four_box_tests_bit_for_bit() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("skipped: this CPU has no AVX2");
            return;
        }
        let mut rng = crate::sampling::Rng::for_sample(3, 0, 0);
        let mut value = |scale: f64| ((rng.uniform() - 0.5) * scale) as f32;
        let mut entered = 0;
        for case in 0..4000 {
            let mut planes = [[0.0f32; 8]; 6];
            for slot in 0..8 {
                for axis in 0..3 {
                    let (a, b) = (value(8.0), value(8.0));
                    (planes[axis][slot], planes[axis + 3][slot]) = (a.min(b), a.max(b));
                }
                if case % 5 == slot {
                    (planes[0][slot], planes[3][slot]) = (f32::INFINITY, f32::NEG_INFINITY);
                }
            }
            let mut dir = Vec3::new(value(2.0).into(), value(2.0).into(), value(2.0).into());
            if case % 3 == 0 {
                dir[case % 9 / 3] = 0.0;
            }
            let origin = Vec3::new(value(12.0).into(), value(12.0).into(), value(12.0).into());
            let ray = SlabRay::new(origin, dir, if case % 7 == 0 { 0.5 } else { 0.0 });
            let t_max = if case % 2 == 0 { f32::INFINITY } else { value(10.0).abs() };
            // SAFETY: the CPU has AVX2 (checked above).
            let (enter, mask) = unsafe { test8_avx2(&ray, &planes, t_max) };
            let half = |h: usize| ray.test(|r| Vec4::from_slice(&planes[r][4 * h..4 * h + 4]), t_max);
            let ((lo, lo_mask), (hi, hi_mask)) = (half(0), half(1));
            let want: Vec<u32> = lo.to_array().iter().chain(&hi.to_array()).map(|v| v.to_bits()).collect();
            assert_eq!(enter.map(f32::to_bits).to_vec(), want, "case {case}: entry distances");
            assert_eq!(mask, lo_mask | hi_mask << 4, "case {case}: mask");
            entered += mask.count_ones();
        }
        assert!(entered > 1000, "the cases enter boxes ({entered})");
    }

    #[test]
    fn f64_origins_between_f32_values_are_bracketed() {
        // A box whose face is the f32 just above an f64 origin coordinate.
        let o = 1.0 + 1e-9;
        let face = (o as f32).next_up();
        let ray = SlabRay::new(Vec3::new(o, 0.5, -1.0), Vec3::Z, 0.0);
        assert_eq!(ray.test(rows([face - 1.0, 0.0, 0.0], [face, 1.0, 1.0]), f32::INFINITY).1, 0b1111);
    }
}
