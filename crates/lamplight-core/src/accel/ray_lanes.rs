//! Four rays at once against every object of a small scene of rectangles and
//! boxes (a Cornell box), each ray in one lane of an AVX2 register: the
//! closest-hit and shadow queries of the path tracer's lanes
//! (`integrators/path_lanes.rs`).
//!
//! With one ray at a time, the flat walk (`bvh.rs`) tests every object's box,
//! then the entered objects nearest first: 408 instructions a closest hit and
//! 300 a shadow ray in the path-traced Cornell box, a dependent chain of
//! branches (issue 24). Four rays side by side share each object's
//! parameters, and each object costs about forty vector instructions for the
//! four. Testing each object's own shape for every ray, with no box first,
//! suits a handful of objects; the lanes are built only for at most
//! [`super::FLAT_MAX`].
//!
//! **The same answer as the walk, bit for bit.** Each lane runs its shape's
//! test with the IEEE operations of the shape's scalar code, in the same order
//! ([`crate::shapes::Rectangle`]'s plane and dual basis,
//! [`crate::shapes::Cuboid`]'s slabs and face): Rust never fuses a multiply
//! and an add, and `vmaxpd b, a` is the scalar `if b > a { b } else { a }`,
//! NaN and signed zeros included. A ray whose nearest hit is nearer than every
//! other object's gets that object, that parameter and that face, as the walk
//! would. Where two objects are hit at exactly the same distance (a box
//! standing on the floor), the walk's order decides: the lane is marked a tie
//! and its caller asks the walk. A shadow ray is blocked by any opaque object
//! but the light's own, in any order.
//!
//! Written by hand with `std::arch`, as the tracer's heart: LLVM's vectoriser
//! kept masks of `bool` scalar (`bench/lanes_probe`, BENCHMARKS.md session 31).
//! A test object-parallel instead (one ray against four objects) ran 9 % more
//! instructions than the walk (BENCHMARKS.md, session 32).

use crate::math::Vec3;
use crate::ray::Ray;
use glam::DMat3;

/// A rectangle's test in a lane: [`crate::shapes::Rectangle`]'s corner, unit
/// normal and the dual basis that gives `(u, v)` of a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectangleLane {
    /// A corner.
    pub corner: Vec3,
    /// The unit normal, the hit's normal.
    pub normal: Vec3,
    /// `dual_u . (p - corner)` is `u`.
    pub dual_u: Vec3,
    /// `dual_v . (p - corner)` is `v`.
    pub dual_v: Vec3,
    /// The edges from the corner (for sampling a point of an emitting rectangle).
    pub edge_u: Vec3,
    /// The second edge.
    pub edge_v: Vec3,
}

/// A box's test in a lane: [`crate::shapes::Cuboid`]'s map to its local
/// frame, its slab planes seen from there, and its faces' normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlabLane {
    /// The linear part of the world-to-local map.
    pub linear: DMat3,
    /// The low slab planes, less the map's translation.
    pub lo: Vec3,
    /// The high slab planes, less the map's translation.
    pub hi: Vec3,
    /// The outward unit normal of face `2 * axis + side` (`Cuboid::face_normal`).
    pub normals: [Vec3; 6],
}

/// A shape whose test runs in a lane ([`crate::shapes::Shape::lane`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LaneShape {
    /// A parallelogram.
    Rectangle(RectangleLane),
    /// A box under an affine map.
    Slab(SlabLane),
}

impl LaneShape {
    /// The outward normal of a hit on face `face` (0 for a rectangle).
    #[inline]
    pub fn normal(&self, face: usize) -> Vec3 {
        match self {
            LaneShape::Rectangle(r) => r.normal,
            LaneShape::Slab(b) => b.normals[face],
        }
    }
}

/// The nearest hits of four rays ([`ObjectLanes::closest`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Nearest4 {
    /// Per lane, the hit's ray parameter (`inf` where none).
    pub t: [f64; 4],
    /// Per lane, the object's index in the build list.
    pub slot: [u32; 4],
    /// Per lane, the face hit (a box's `2 * axis + side`; 0 on a rectangle).
    pub face: [u32; 4],
    /// Lanes hit (bit `i` for lane `i`).
    pub hit: u8,
    /// Lanes whose nearest hit ties between two objects: the walk decides.
    pub tie: u8,
}

/// Every object's test, in lanes (module doc).
#[derive(Clone, Debug)]
pub struct ObjectLanes {
    shapes: Vec<LaneShape>,
    /// The rectangles and the boxes apart, each with its index in `shapes`,
    /// so that the queries' loops do not branch on the kind.
    rectangles: Vec<(RectangleLane, u32)>,
    slabs: Vec<(SlabLane, u32)>,
    /// Per object: whether it stops shadow rays.
    opaque: Vec<bool>,
    /// Per object: its number in the scene (the shadow query's `ignore`).
    objects: Vec<u32>,
}

impl ObjectLanes {
    /// The lanes of `objects`: each its shape, whether it stops shadow rays and
    /// its number in the scene. `None` for none, or more than [`super::FLAT_MAX`].
    pub fn build(objects: &[(LaneShape, bool, u32)]) -> Option<ObjectLanes> {
        if objects.is_empty() || objects.len() > super::FLAT_MAX {
            return None;
        }
        let slot = |i: usize| i as u32;
        Some(ObjectLanes {
            rectangles: objects
                .iter()
                .enumerate()
                .filter_map(|(i, o)| if let LaneShape::Rectangle(r) = o.0 { Some((r, slot(i))) } else { None })
                .collect(),
            slabs: objects
                .iter()
                .enumerate()
                .filter_map(|(i, o)| if let LaneShape::Slab(b) = o.0 { Some((b, slot(i))) } else { None })
                .collect(),
            shapes: objects.iter().map(|o| o.0).collect(),
            opaque: objects.iter().map(|o| o.1).collect(),
            objects: objects.iter().map(|o| o.2).collect(),
        })
    }

    /// Object `slot`'s shape.
    #[inline]
    pub fn shape(&self, slot: u32) -> &LaneShape {
        &self.shapes[slot as usize]
    }

    /// How many objects it holds.
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Whether it holds none (never, once built).
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::*;
    use std::arch::x86_64::*;

    /// The four rays in registers.
    pub(crate) struct Rays {
        pub(crate) o: [__m256d; 3],
        pub(crate) d: [__m256d; 3],
    }

    /// The four rays, coordinate by coordinate, gathered from their fields
    /// in registers: written lane by lane into memory and read back as one
    /// vector, each coordinate would wait on a failed store-forwarding.
    #[inline(always)]
    pub(crate) unsafe fn rays(q: &[Ray; 4]) -> Rays {
        let o = |axis: usize| _mm256_setr_pd(q[0].origin[axis], q[1].origin[axis], q[2].origin[axis], q[3].origin[axis]);
        let d = |axis: usize| _mm256_setr_pd(q[0].dir[axis], q[1].dir[axis], q[2].dir[axis], q[3].dir[axis]);
        Rays { o: [o(0), o(1), o(2)], d: [d(0), d(1), d(2)] }
    }

    /// Four rays given coordinate by coordinate.
    #[inline(always)]
    unsafe fn coordinates(origin: [&[f64; 4]; 3], dir: [&[f64; 4]; 3]) -> Rays {
        let l = |a: &[f64; 4]| _mm256_loadu_pd(a.as_ptr());
        Rays { o: [l(origin[0]), l(origin[1]), l(origin[2])], d: [l(dir[0]), l(dir[1]), l(dir[2])] }
    }

    #[inline(always)]
    pub(super) unsafe fn splat(v: Vec3) -> [__m256d; 3] {
        [_mm256_set1_pd(v.x), _mm256_set1_pd(v.y), _mm256_set1_pd(v.z)]
    }

    /// `a.x * b.x + a.y * b.y + a.z * b.z`, in glam's order.
    #[inline(always)]
    pub(super) unsafe fn dot(a: [__m256d; 3], b: [__m256d; 3]) -> __m256d {
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a[0], b[0]), _mm256_mul_pd(a[1], b[1])), _mm256_mul_pd(a[2], b[2]))
    }

    /// `Rectangle::hit_t` in each lane: the parameter and an all-ones mask
    /// where it is a hit in `(0, t_max)`.
    #[inline(always)]
    pub(crate) unsafe fn rectangle(s: &RectangleLane, r: &Rays, t_max: __m256d) -> (__m256d, __m256d) {
        let zero = _mm256_setzero_pd();
        let n = splat(s.normal);
        let c = splat(s.corner);
        let denom = dot(r.d, n);
        let to_corner = [_mm256_sub_pd(c[0], r.o[0]), _mm256_sub_pd(c[1], r.o[1]), _mm256_sub_pd(c[2], r.o[2])];
        let t = _mm256_div_pd(dot(to_corner, n), denom);
        let ok = _mm256_and_pd(
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_NEQ_OQ>(denom, zero), _mm256_cmp_pd::<_CMP_GT_OQ>(t, zero)),
            _mm256_cmp_pd::<_CMP_LT_OQ>(t, t_max),
        );
        // `ray.at(t) - corner`, the point as origin + dir * t.
        let local = [
            _mm256_sub_pd(_mm256_add_pd(r.o[0], _mm256_mul_pd(r.d[0], t)), c[0]),
            _mm256_sub_pd(_mm256_add_pd(r.o[1], _mm256_mul_pd(r.d[1], t)), c[1]),
            _mm256_sub_pd(_mm256_add_pd(r.o[2], _mm256_mul_pd(r.d[2], t)), c[2]),
        ];
        let one = _mm256_set1_pd(1.0);
        let u = dot(local, splat(s.dual_u));
        let v = dot(local, splat(s.dual_v));
        let inside = _mm256_and_pd(
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(zero, u), _mm256_cmp_pd::<_CMP_LE_OQ>(u, one)),
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(zero, v), _mm256_cmp_pd::<_CMP_LE_OQ>(v, one)),
        );
        (t, _mm256_and_pd(ok, inside))
    }

    /// `Cuboid::hit` in each lane: the entry of the slab interval where it
    /// lies in `(0, t_max)`, else its exit; the mask; and, when `FACE`, the
    /// face as `SlabHit::face` names it (in `f64` lanes).
    #[inline(always)]
    unsafe fn slab<const FACE: bool>(s: &SlabLane, r: &Rays, t_max: __m256d) -> (__m256d, __m256d, __m256d) {
        let m = s.linear;
        // `linear * v`: column 0 times v.x, plus column 1 times v.y, plus column 2 times v.z.
        let map = |v: &[__m256d; 3], row: usize| {
            _mm256_add_pd(
                _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(m.x_axis[row]), v[0]), _mm256_mul_pd(_mm256_set1_pd(m.y_axis[row]), v[1])),
                _mm256_mul_pd(_mm256_set1_pd(m.z_axis[row]), v[2]),
            )
        };
        let one = _mm256_set1_pd(1.0);
        let zero = _mm256_setzero_pd();
        let mut enter = _mm256_set1_pd(f64::NEG_INFINITY);
        let mut exit = _mm256_set1_pd(f64::INFINITY);
        let mut near = [zero; 3];
        let mut far = [zero; 3];
        let mut up = [zero; 3];
        for axis in 0..3 {
            let o = map(&r.o, axis);
            let inv = _mm256_div_pd(one, map(&r.d, axis));
            let to_lo = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(s.lo[axis]), o), inv);
            let to_hi = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(s.hi[axis]), o), inv);
            up[axis] = _mm256_cmp_pd::<_CMP_GE_OQ>(inv, zero);
            near[axis] = _mm256_blendv_pd(to_hi, to_lo, up[axis]);
            far[axis] = _mm256_blendv_pd(to_lo, to_hi, up[axis]);
            // `if b > a { b } else { a }` is `vmaxpd b, a`; `if b < a` is `vminpd b, a`.
            enter = _mm256_max_pd(near[axis], enter);
            exit = _mm256_min_pd(far[axis], exit);
        }
        let ok = _mm256_cmp_pd::<_CMP_LE_OQ>(enter, exit);
        let entering = _mm256_cmp_pd::<_CMP_GT_OQ>(enter, zero);
        let enter_ok = _mm256_cmp_pd::<_CMP_LT_OQ>(enter, t_max);
        let exit_ok = _mm256_and_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(exit, zero), _mm256_cmp_pd::<_CMP_LT_OQ>(exit, t_max));
        let t = _mm256_blendv_pd(exit, enter, entering);
        let ok = _mm256_and_pd(ok, _mm256_blendv_pd(exit_ok, enter_ok, entering));
        if !FACE {
            return (t, ok, zero);
        }
        // The axis whose bound is `t` (x, else y, else z), and the side:
        // `2 * axis + (entering == up[axis])`.
        let bound = |axis: usize| _mm256_blendv_pd(far[axis], near[axis], entering);
        let on_x = _mm256_cmp_pd::<_CMP_EQ_OQ>(bound(0), t);
        let on_y = _mm256_cmp_pd::<_CMP_EQ_OQ>(bound(1), t);
        let side =
            |axis: usize| _mm256_and_pd(_mm256_xor_pd(_mm256_xor_pd(entering, up[axis]), _mm256_castsi256_pd(_mm256_set1_epi64x(-1))), one);
        let z = _mm256_add_pd(_mm256_set1_pd(4.0), side(2));
        let y = _mm256_add_pd(_mm256_set1_pd(2.0), side(1));
        let face = _mm256_blendv_pd(_mm256_blendv_pd(z, y, on_y), side(0), on_x);
        (t, ok, face)
    }

    impl ObjectLanes {
        /// The nearest object each ray of `rays` hits in `(0, t_max)`, for the
        /// lanes set in `active` (module doc).
        ///
        /// # Safety
        /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
        #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
        #[inline]
        pub unsafe fn closest(&self, rays: &[Ray; 4], t_max: f64, active: u8) -> Nearest4 {
            let mut out = Nearest4::default();
            self.closest_dispatched(&self::rays(rays), t_max, active, &mut out);
            out
        }

        /// [`ObjectLanes::closest`] of rays given coordinate by coordinate
        /// (lane `k` of `origin[axis]` is ray `k`'s origin on that axis),
        /// written into `out` (a copy of the answer right after the query's
        /// stores would wait on them).
        ///
        /// # Safety
        /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
        #[inline(always)]
        pub unsafe fn closest_coordinates(&self, origin: [&[f64; 4]; 3], dir: [&[f64; 4]; 3], t_max: f64, active: u8, out: &mut Nearest4) {
            self.closest_dispatched(&coordinates(origin, dir), t_max, active, out);
        }

        /// The lanes of `active` whose segment from the origin along the unit
        /// direction over `(0, distance[lane])` meets an opaque object other
        /// than object `ignore[lane]` (`u32::MAX` for none).
        ///
        /// # Safety
        /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
        #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
        #[inline]
        pub unsafe fn blocked(&self, rays: &[Ray; 4], distance: &[f64; 4], ignore: &[u32; 4], active: u8) -> u8 {
            self.blocked_dispatched(&self::rays(rays), distance, ignore, active)
        }

        /// [`ObjectLanes::blocked`] of rays given coordinate by coordinate.
        ///
        /// # Safety
        /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
        #[inline(always)]
        pub unsafe fn blocked_coordinates(
            &self,
            origin: [&[f64; 4]; 3],
            dir: [&[f64; 4]; 3],
            distance: &[f64; 4],
            ignore: &[u32; 4],
            active: u8,
        ) -> u8 {
            self.blocked_dispatched(&coordinates(origin, dir), distance, ignore, active)
        }

        /// The closest-hit query's body, through its compilation for this CPU.
        /// The answer is written into `out` where the caller keeps it: returned
        /// by value, it was copied in 16-byte pieces that straddled the query's
        /// own stores, and each piece waited on a failed store-forwarding.
        #[inline(always)]
        unsafe fn closest_dispatched(&self, r: &Rays, t_max: f64, active: u8, out: &mut Nearest4) {
            if crate::cpu::avx512_features() {
                self.closest_in_avx512(r, t_max, active, out)
            } else {
                self.closest_in(r, t_max, active, out)
            }
        }

        /// The shadow query's body, through its compilation for this CPU.
        #[inline(always)]
        unsafe fn blocked_dispatched(&self, r: &Rays, distance: &[f64; 4], ignore: &[u32; 4], active: u8) -> u8 {
            if crate::cpu::avx512_features() {
                self.blocked_in_avx512(r, distance, ignore, active)
            } else {
                self.blocked_in(r, distance, ignore, active)
            }
        }

        /// [`ObjectLanes::closest`] with the AVX2 compilation whatever the
        /// CPU, for the test that compares the two.
        #[cfg(test)]
        pub(in crate::accel) unsafe fn closest_avx2(&self, rays: &[Ray; 4], t_max: f64, active: u8) -> Nearest4 {
            let mut out = Nearest4::default();
            self.closest_in(&self::rays(rays), t_max, active, &mut out);
            out
        }

        /// [`ObjectLanes::blocked`] with the AVX2 compilation whatever the CPU.
        #[cfg(test)]
        pub(in crate::accel) unsafe fn blocked_avx2(&self, rays: &[Ray; 4], distance: &[f64; 4], ignore: &[u32; 4], active: u8) -> u8 {
            self.blocked_in(&self::rays(rays), distance, ignore, active)
        }
    }

    /// The queries' bodies, each compiled for its features itself so that
    /// its closures are too (as plain inlined functions their intrinsics
    /// became calls: 2.7x the time). Twice: for AVX2, and for
    /// [`crate::cpu::AVX512_FEATURES`], where the same intrinsics get 32
    /// registers (no spills) and compare into mask registers (no blends):
    /// the same operations, so the same bits.
    macro_rules! bodies {
        ($features:literal, $closest:ident, $blocked:ident) => {
            impl ObjectLanes {
                #[target_feature(enable = $features)]
                #[inline]
                unsafe fn $closest(&self, r: &Rays, t_max: f64, active: u8, out: &mut Nearest4) {
                    let t_max = _mm256_set1_pd(t_max);
                    let live = _mm256_castsi256_pd(_mm256_cmpgt_epi64(
                        _mm256_and_si256(_mm256_set1_epi64x(i64::from(active)), _mm256_setr_epi64x(1, 2, 4, 8)),
                        _mm256_setzero_si256(),
                    ));
                    let mut best = _mm256_set1_pd(f64::INFINITY);
                    let mut slot = _mm256_setzero_pd();
                    let mut face = _mm256_setzero_pd();
                    let mut tie = _mm256_setzero_pd();
                    // Keeps the nearer of each lane's best so far and object `k`'s hit.
                    let mut keep = |k: u32, t: __m256d, ok: __m256d, f: __m256d| {
                        let ok = _mm256_and_pd(ok, live);
                        let closer = _mm256_and_pd(ok, _mm256_cmp_pd::<_CMP_LT_OQ>(t, best));
                        let equal = _mm256_and_pd(ok, _mm256_cmp_pd::<_CMP_EQ_OQ>(t, best));
                        tie = _mm256_or_pd(_mm256_andnot_pd(closer, tie), equal);
                        best = _mm256_blendv_pd(best, t, closer);
                        slot = _mm256_blendv_pd(slot, _mm256_set1_pd(f64::from(k)), closer);
                        face = _mm256_blendv_pd(face, f, closer);
                    };
                    for (s, k) in &self.rectangles {
                        let (t, ok) = rectangle(s, r, t_max);
                        keep(*k, t, ok, _mm256_setzero_pd());
                    }
                    for (s, k) in &self.slabs {
                        let (t, ok, f) = slab::<true>(s, r, t_max);
                        keep(*k, t, ok, f);
                    }
                    _mm256_storeu_pd(out.t.as_mut_ptr(), best);
                    // Small whole numbers in `f64`: converted exactly.
                    _mm_storeu_si128(out.slot.as_mut_ptr().cast(), _mm256_cvttpd_epi32(slot));
                    _mm_storeu_si128(out.face.as_mut_ptr().cast(), _mm256_cvttpd_epi32(face));
                    out.hit = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(best, _mm256_set1_pd(f64::INFINITY))) as u8;
                    out.tie = _mm256_movemask_pd(tie) as u8;
                }

                #[target_feature(enable = $features)]
                #[inline]
                unsafe fn $blocked(&self, r: &Rays, distance: &[f64; 4], ignored: &[u32; 4], active: u8) -> u8 {
                    let t_max = _mm256_loadu_pd(distance.as_ptr());
                    let ignore =
                        _mm256_setr_epi64x(i64::from(ignored[0]), i64::from(ignored[1]), i64::from(ignored[2]), i64::from(ignored[3]));
                    // An object that blocks no active lane whatever its test
                    // answers (not opaque, or the one every active lane
                    // ignores: a light's own shape for its shadow rays) is
                    // not tested.
                    let first = ignored[active.trailing_zeros().min(3) as usize];
                    let shared = (0..4).all(|l| active & (1 << l) == 0 || ignored[l] == first);
                    let all_ignore = if shared { first } else { u32::MAX };
                    let idle = |k: u32| {
                        let k = k as usize;
                        !self.opaque[k] || self.objects[k] == all_ignore
                    };
                    let mut blocked = 0u8;
                    // The lanes object `k` blocks.
                    let blocks = |k: u32, ok: __m256d| -> u8 {
                        let k = k as usize;
                        let own = _mm256_castsi256_pd(_mm256_cmpeq_epi64(ignore, _mm256_set1_epi64x(i64::from(self.objects[k]))));
                        if self.opaque[k] {
                            _mm256_movemask_pd(_mm256_andnot_pd(own, ok)) as u8
                        } else {
                            0
                        }
                    };
                    for (s, k) in &self.rectangles {
                        if idle(*k) {
                            continue;
                        }
                        blocked |= blocks(*k, rectangle(s, r, t_max).1);
                        if blocked & active == active {
                            return active;
                        }
                    }
                    for (s, k) in &self.slabs {
                        if idle(*k) {
                            continue;
                        }
                        blocked |= blocks(*k, slab::<false>(s, r, t_max).1);
                        if blocked & active == active {
                            return active;
                        }
                    }
                    blocked & active
                }
            }
        };
    }
    bodies!("avx2,bmi1,bmi2,lzcnt,popcnt", closest_in, blocked_in);
    bodies!("avx2,bmi1,bmi2,lzcnt,popcnt,gfni,avx512f,avx512dq,avx512vl,avx512bw", closest_in_avx512, blocked_in_avx512);
}

#[cfg(target_arch = "x86_64")]
mod balls;
/// The lane tests the eye's four-ray search uses (`scene/eye_lanes.rs`).
#[cfg(target_arch = "x86_64")]
pub(crate) use avx2::{rays, rectangle, Rays};
#[cfg(target_arch = "x86_64")]
pub(crate) use balls::sphere;

#[cfg(test)]
mod tests;
