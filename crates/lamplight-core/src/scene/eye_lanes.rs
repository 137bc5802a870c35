//! Four camera rays at once through the eye's buffer (`scene/eye.rs`): the
//! rays of four neighbouring pixels mostly look up the same cell, so they
//! share one walk along its list, the balls and rectangles on it tested in
//! the four lanes of AVX2 registers (`accel/ray_lanes.rs`), any other shape
//! by its own test lane by lane. A ray from the eye spent some 430
//! instructions in the one-ray search of `spheres` and `luxo`, for one or
//! two tests: most went to looking up its cell and keeping its nearest hit
//! (issue 24).
//!
//! **The same answers, bit for bit.** Each lane keeps what the one-ray
//! search keeps, with the same rules: an object is asked up to the float
//! past the nearest hit so far; a nearer hit replaces it; an equal one is a
//! tie, which the walk decides; a lane stops at the first object of the
//! cell whose reach lies beyond its nearest hit. The lane tests compute
//! the scalar tests' IEEE operations in their order (Rust never fuses a
//! multiply and an add). The hit handed back is the one its object's own
//! test gives, asked again with the bound it was found under (or kept from
//! it). The lanes are grouped by the list their cell holds, each group
//! searched together; a lane whose cell has no list walks the BVH, as one
//! ray does, and rays that leave from elsewhere and scenes with unbounded
//! objects go to the one-ray query.

use super::{Hit, Scene};
use crate::ray::Ray;

#[cfg(target_arch = "x86_64")]
impl Scene {
    /// [`Scene::first_intersect`] of each of `rays` with no bound on `t`,
    /// written into `out`: the same answers, four rays from the eye at once
    /// where they share their cell (module doc).
    ///
    /// # Safety
    /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    #[inline(never)]
    pub(crate) unsafe fn first_hits_from_eye(&self, rays: &[Ray; 4], out: &mut [Option<Hit>; 4]) {
        if !self.first_hits_shared(rays, out) {
            for (ray, hit) in rays.iter().zip(out.iter_mut()) {
                *hit = self.first_intersect(ray, f64::INFINITY);
            }
        }
    }

    /// The shared search of [`Scene::first_hits_from_eye`]: the lanes
    /// grouped by their cell's list, each group searched together; false
    /// (and `out` untouched) where the rays must go one by one.
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    #[inline]
    unsafe fn first_hits_shared(&self, rays: &[Ray; 4], out: &mut [Option<Hit>; 4]) -> bool {
        let Some(eye) = self.eye_buffer.as_ref() else { return false };
        if !self.unbounded.is_empty() || rays.iter().any(|r| r.origin != self.eye) {
            return false;
        }
        let r = crate::accel::lane_rays(rays);
        let cells = eye.cells(r.d);
        let mut pending = 0b1111u8;
        while pending != 0 {
            let lead = pending.trailing_zeros() as usize;
            let mut group = 0u8;
            for (l, &cell) in cells.iter().enumerate() {
                if pending & (1 << l) != 0 && cell == cells[lead] {
                    group |= 1 << l;
                }
            }
            pending &= !group;
            match eye.list_of_cell(cells[lead]) {
                Some(cell) => self.search_lanes(eye, rays, &r, (eye.always(), cell), group, out),
                // No list: the walk answers, as it does for one ray.
                None => {
                    for l in (0..4).filter(|l| group & (1 << l) != 0) {
                        out[l] = self.first_intersect(&rays[l], f64::INFINITY);
                    }
                }
            }
        }
        true
    }

    /// The one-ray search of `scene/eye.rs` for the lanes `group` of `rays`
    /// (`r` in registers), whose cell lists `cell` after the eye's `always`,
    /// written into their places of `out`.
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    #[inline]
    unsafe fn search_lanes(
        &self,
        eye: &crate::accel::EyeBuffer,
        rays: &[Ray; 4],
        r: &crate::accel::LaneRays,
        (always, cell): (&[u32], &[u32]),
        group: u8,
        out: &mut [Option<Hit>; 4],
    ) {
        use crate::accel::LaneShape;
        use crate::accel::{rectangle_lanes as rectangle, sphere_lanes as sphere};
        use crate::shapes::{Inlined, SurfaceHit};
        use std::arch::x86_64::*;

        let mut closest = _mm256_set1_pd(f64::INFINITY);
        // `closest`'s next float up in each lane: infinity stays infinity.
        let mut limit = closest;
        // Per lane: the object hit nearest (`u32::MAX`: none), the limit it
        // was found under, the hit itself where a lane's own test found it
        // (the lane tests give only the parameter, and their shapes' tests
        // are cheap to ask again), and whether a later object ties with it.
        let mut best = [u32::MAX; 4];
        let mut found_under = [f64::INFINITY; 4];
        let mut found: [Option<SurfaceHit>; 4] = [None; 4];
        let mut hits: [Option<SurfaceHit>; 4] = [None; 4];
        let mut tie = 0u8;
        // Lanes still walking the cell's list.
        let mut live = group;
        for (k, &i) in always.iter().chain(cell).enumerate() {
            let active = if k < always.len() {
                group
            } else {
                // The list is sorted by reach: a lane whose nearest hit lies
                // before this object's reach is done with the whole list.
                let beyond = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(_mm256_set1_pd(eye.reach(i)), closest)) as u8;
                live &= !beyond;
                if live == 0 {
                    break;
                }
                live
            };
            let prim = &self.bounded[i as usize];
            // Whether the hits came from the object's own test (kept in `hits`).
            let mut own = false;
            let (t, hit) = match (&prim.inlined, prim.masked) {
                (Some(Inlined::Sphere(s)), false) => sphere(s.center, s.radius, r, limit),
                (Some(Inlined::Rectangle(rect)), false) => match crate::shapes::Shape::lane(&**rect) {
                    Some(LaneShape::Rectangle(lane)) => rectangle(&lane, r, limit),
                    _ => unreachable!("a rectangle's lane is a rectangle"),
                },
                _ => {
                    // Lane by lane, the object's own test.
                    own = true;
                    let mut bound = [0.0; 4];
                    _mm256_storeu_pd(bound.as_mut_ptr(), limit);
                    let (mut t, mut hit) = ([0.0; 4], [0.0f64; 4]);
                    for l in (0..4).filter(|l| active & (1 << l) != 0) {
                        if let Some(h) = self.hit_object(prim, &rays[l], bound[l]) {
                            t[l] = h.t;
                            hit[l] = f64::from_bits(u64::MAX);
                            hits[l] = Some(h);
                        }
                    }
                    (_mm256_loadu_pd(t.as_ptr()), _mm256_loadu_pd(hit.as_ptr()))
                }
            };
            let hit = _mm256_movemask_pd(hit) as u8 & active;
            if hit == 0 {
                continue;
            }
            let closer = hit & _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(t, closest)) as u8;
            // A hit not nearer is one at exactly `closest`: a tie, where a hit came before.
            for (l, &b) in best.iter().enumerate() {
                if hit & !closer & (1 << l) != 0 && b != u32::MAX {
                    tie |= 1 << l;
                }
            }
            if closer == 0 {
                continue;
            }
            let mut bound = [0.0; 4];
            _mm256_storeu_pd(bound.as_mut_ptr(), limit);
            for l in (0..4).filter(|l| closer & (1 << l) != 0) {
                best[l] = i;
                found_under[l] = bound[l];
                found[l] = if own { hits[l] } else { None };
                tie &= !(1 << l);
            }
            let mask = _mm256_castsi256_pd(_mm256_cmpgt_epi64(
                _mm256_and_si256(_mm256_set1_epi64x(i64::from(closer)), _mm256_setr_epi64x(1, 2, 4, 8)),
                _mm256_setzero_si256(),
            ));
            closest = _mm256_blendv_pd(closest, t, mask);
            // A hit lies in `(0, limit)`, so it is positive and finite: its
            // next float up is the next bit pattern.
            let up = _mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(t), _mm256_set1_epi64x(1)));
            limit = _mm256_blendv_pd(limit, up, mask);
        }
        for l in (0..4).filter(|l| group & (1 << l) != 0) {
            let ray = &rays[l];
            // Each case writes `out[l]` itself: one value chosen among them
            // was built in a temporary and copied out with loads wider than
            // its stores, a stall on every camera ray's hit (issue 24).
            if tie & (1 << l) != 0 {
                out[l] = self.first_intersect_walk_avx2(ray, f64::INFINITY);
                continue;
            }
            if best[l] == u32::MAX {
                out[l] = None;
                continue;
            }
            let prim = &self.bounded[best[l] as usize];
            match found[l].or_else(|| self.hit_object(prim, ray, found_under[l])) {
                Some(h) => out[l] = Some(self.hit_record(ray, prim.object as usize, h)),
                // Never: the same test, asked the same question.
                None => out[l] = self.first_intersect(ray, f64::INFINITY),
            }
        }
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::super::eye::tests::{mixed_scene_with, pinhole, EYE};
    use crate::math::Vec3;
    use crate::ray::Ray;

    /// Packets of four rays from the eye, neighbours a thousandth of a radian
    /// apart (one cell), scattered ones (several cells), rays at the ball
    /// placed twice and the two rectangles in one plane (ties), and packets
    /// with a ray not of unit length or not from the eye: each answer is the
    /// one-ray query's, bit for bit. With an infinite plane in the scene the
    /// rays go one by one.
    #[test]
    fn four_rays_get_the_one_ray_answers() {
        if !crate::cpu::avx2_features() {
            eprintln!("skipped: this CPU lacks AVX2, and the packets run only there");
            return;
        }
        for plane in [false, true] {
            let scene = mixed_scene_with(pinhole(), plane);
            let mut rng = crate::sampling::Rng::for_sample(21, 0, 0);
            let mut rand = move || rng.uniform();
            let (mut shared, mut hits) = (0, 0);
            for k in 0..8_000 {
                let target = |rand: &mut dyn FnMut() -> f64| match k % 10 {
                    0 => Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 100.0,
                    1 => {
                        [Vec3::new(0.0, 1.0, 0.0), Vec3::new(-1.0, 1.0, 3.0)][k % 20 / 10]
                            + Vec3::new(rand() - 0.5, rand() - 0.5, 0.0) * 0.8
                    }
                    _ => Vec3::new(rand() * 12.0 - 6.0, rand() * 4.0, rand() * 12.0 - 6.0),
                };
                let centre = (target(&mut rand) - EYE).normalize();
                let mut rays: [Ray; 4] = std::array::from_fn(|l| {
                    let dir = if k % 3 == 0 {
                        (target(&mut rand) - EYE).normalize()
                    } else {
                        (centre + Vec3::new(l as f64 * 1e-3, (l / 2) as f64 * 1e-3, 0.0)).normalize()
                    };
                    Ray::unit(EYE, dir)
                });
                if k % 50 == 7 {
                    rays[2] = Ray::unit(EYE, rays[2].dir * 1.5);
                }
                if k % 50 == 9 {
                    rays[1] = Ray::unit(EYE + Vec3::new(0.0, 1e-3, 0.0), rays[1].dir);
                }
                let mut out = [None, None, None, None];
                // SAFETY: the CPU has AVX2 (checked above).
                unsafe {
                    shared += usize::from(scene.first_hits_shared(&rays, &mut out.clone()));
                    scene.first_hits_from_eye(&rays, &mut out);
                }
                for (ray, answer) in rays.iter().zip(&out) {
                    assert_eq!(*answer, scene.first_intersect(ray, f64::INFINITY), "ray {ray:?}");
                    hits += usize::from(answer.is_some());
                }
            }
            if plane {
                assert_eq!(shared, 0, "an unbounded object: one by one");
            } else {
                assert!(shared > 7_500, "only {shared} packets searched together");
            }
            assert!(hits > 15_000, "only {hits} hits");
        }
    }
}
