//! The eye's buffer (POV-Ray's "vista buffer", Haines's first-hit speed-up):
//! a [`LightBuffer`] around the camera's eye, listing every object, so that a
//! camera ray looks at the objects of one cell of directions instead of
//! walking the scene's BVH.
//!
//! A ray that leaves the eye is seen from the eye, at every point, in its own
//! direction, so the cell of that direction lists every object it can meet
//! (`light_buffer.rs`, with the ray starting at the centre). Each list is
//! sorted by how near the object's box comes to the eye ([`EyeBuffer::reach`]),
//! so the search stops at the first object whose box lies beyond the nearest
//! hit so far: in the POV-Ray `spheres` scene a camera ray tests the floor and
//! one or two balls, where the walk tested about two nodes of eight boxes and
//! ordered them.
//!
//! **The same answer as the walk.** Where the nearest hit is nearer than every
//! other object's, any search that tests every candidate that could be nearer
//! finds it (the search skips only boxes beyond the nearest hit so far), and
//! the object's test reports the same hit for any `t_max` above it
//! ([`crate::shapes::Shape::hit_ignores_t_max`], which every object must
//! have for the buffer to be built). Where two objects are hit at exactly the
//! same distance, the walk's order decides, so the search hands such a ray
//! back to the walk: each object is asked up to the float just past the
//! nearest hit so far, which shows a hit at exactly that distance.
//!
//! Written by hand, as the light buffer: it is part of the tracer's heart.

use super::{Aabb, LightBuffer};
use crate::math::{max_abs, Vec3};

/// Relative allowance of [`EyeBuffer::reach`] for the rounding of a reported
/// hit and of a unit direction: far above either (about `1e-15`), far below
/// any distance between objects that matters for stopping early.
const REACH_ALLOWANCE: f64 = 1e-9;

/// The direction cells around the eye, each listing the objects that may lie
/// in its directions, nearest box first.
#[derive(Clone, Debug)]
pub struct EyeBuffer {
    cells: LightBuffer,
    /// Per object: a lower bound on the ray parameter of any hit on it by a
    /// ray from the eye with a unit direction.
    reach: Vec<f64>,
}

impl EyeBuffer {
    /// The buffer around `eye` for the objects with boxes `boxes` (numbered as
    /// the slice), in a scene whose extent is `scale`; `meets` as for
    /// [`LightBuffer::build`]. `None` where a light buffer would be.
    pub fn build(eye: Vec3, boxes: &[Aabb], meets: impl Fn(usize, &Aabb) -> bool, scale: f64) -> Option<EyeBuffer> {
        let mut cells = LightBuffer::build(eye, boxes, |_| true, meets, scale)?;
        let reach: Vec<f64> = boxes
            .iter()
            .map(|b| {
                let gap = (eye.clamp(b.min, b.max) - eye).length();
                // Infinite boxes (none reach the buffer; kept safe) are near.
                let allowance = REACH_ALLOWANCE * (gap + max_abs(b.min).max(max_abs(b.max)) + max_abs(eye));
                if allowance.is_finite() {
                    (gap - allowance).max(0.0)
                } else {
                    0.0
                }
            })
            .collect();
        cells.sort_lists_by(|i| reach[i as usize]);
        Some(EyeBuffer { cells, reach })
    }

    /// The point the buffer is seen from.
    #[inline(always)]
    pub fn eye(&self) -> Vec3 {
        self.cells.centre()
    }

    /// For a ray from the eye along `dir`: the objects near the eye, which it
    /// tests in any case, and those of its cell, nearest box first. `None`
    /// where the cell lists too many, or `dir` is not of unit length (the
    /// bounds of [`EyeBuffer::reach`] assume it): the caller walks the BVH.
    #[inline(always)]
    pub fn lists(&self, dir: Vec3) -> Option<(&[u32], &[u32])> {
        if (dir.length_squared() - 1.0).abs() > 1e-12 {
            return None;
        }
        Some((self.cells.always(), self.cells.cell_from_centre(dir)?))
    }

    /// [`EyeBuffer::lists`] of four directions at once (lane `l` of each
    /// coordinate), as cell numbers for [`EyeBuffer::list_of_cell`]:
    /// `u32::MAX` where `lists` gives none for a direction not of unit length.
    ///
    /// # Safety
    /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    #[inline]
    pub(crate) unsafe fn cells(&self, d: [std::arch::x86_64::__m256d; 3]) -> [u32; 4] {
        use std::arch::x86_64::*;
        let square = |c: __m256d| _mm256_mul_pd(c, c);
        let length2 = _mm256_add_pd(_mm256_add_pd(square(d[0]), square(d[1])), square(d[2]));
        let off = _mm256_andnot_pd(_mm256_set1_pd(-0.0), _mm256_sub_pd(length2, _mm256_set1_pd(1.0)));
        let not_unit = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(off, _mm256_set1_pd(1e-12)));
        let mut cells = LightBuffer::cells_from_centre(d);
        for (l, cell) in cells.iter_mut().enumerate() {
            if not_unit & (1 << l) != 0 {
                *cell = u32::MAX;
            }
        }
        cells
    }

    /// The objects near the eye, which every ray tests ([`EyeBuffer::lists`]).
    #[inline(always)]
    pub(crate) fn always(&self) -> &[u32] {
        self.cells.always()
    }

    /// The list of cell `cell` of [`EyeBuffer::cells`], nearest box first;
    /// `None` where it lists too many (or for `u32::MAX`).
    #[inline(always)]
    pub(crate) fn list_of_cell(&self, cell: u32) -> Option<&[u32]> {
        self.cells.list_of_cell(cell)
    }

    /// A distance below every hit on object `i` by a ray from the eye: how
    /// near its box comes to the eye, less `REACH_ALLOWANCE` (1e-9) of the sizes
    /// involved. A list can stop at an object whose reach lies beyond the
    /// nearest hit found.
    #[inline(always)]
    pub fn reach(&self, i: u32) -> f64 {
        self.reach[i as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::light_buffer::tests::random_boxes;
    use crate::sampling::Rng;

    /// Random boxes around an eye: every box a ray from the eye passes through
    /// is listed for the ray, and no point of it is nearer than its reach.
    #[test]
    fn rays_from_the_eye_find_every_box_they_cross_listed() {
        let mut rng = Rng::for_sample(9, 0, 0);
        let mut rand = move || rng.uniform();
        for trial in 0..30 {
            let scale = [1e-3, 1.0, 1e4][trial % 3];
            let eye = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 4.0 * scale;
            let boxes = random_boxes(&mut rand, 50, scale, 5, 4.0);
            let Some(buffer) = EyeBuffer::build(eye, &boxes, |_, _| true, 10.0 * scale) else { continue };
            for (k, b) in boxes.iter().enumerate() {
                for _ in 0..30 {
                    let q = b.min + (b.max - b.min) * Vec3::new(rand(), rand(), rand());
                    let away = q - eye;
                    if away.length() == 0.0 {
                        continue;
                    }
                    let dir = away.normalize();
                    let Some((always, cell)) = buffer.lists(dir) else { continue };
                    assert!(always.contains(&(k as u32)) || cell.contains(&(k as u32)), "box {k} not listed towards {q:?}");
                    assert!(buffer.reach(k as u32) <= away.length(), "box {k}: reach beyond a point of it");
                }
            }
            // Each list is sorted by reach.
            for dir in [Vec3::X, -Vec3::Y, Vec3::new(0.3, -0.5, 0.8).normalize()] {
                if let Some((_, cell)) = buffer.lists(dir) {
                    assert!(cell.windows(2).all(|w| buffer.reach(w[0]) <= buffer.reach(w[1])));
                }
            }
        }
    }

    /// Directions that are not of unit length get no list.
    #[test]
    fn non_unit_directions_walk() {
        let boxes = [Aabb { min: Vec3::splat(1.0), max: Vec3::splat(2.0) }];
        let buffer = EyeBuffer::build(Vec3::ZERO, &boxes, |_, _| true, 10.0).unwrap();
        assert!(buffer.lists(Vec3::X).is_some());
        assert!(buffer.lists(Vec3::X * 2.0).is_none());
    }
}
