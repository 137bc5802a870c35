//! The scene's queries for four rays at once ([`ObjectLanes`]), for the path
//! tracer's lanes (`integrators/path/lanes.rs`): the same hits, bit for bit,
//! as [`Scene::first_intersect`] and the same verdicts as
//! [`Scene::transmittance`] gives each ray alone.

use super::{Hit, PrimRef, Scene};
use crate::accel::ObjectLanes;
use crate::ray::Ray;
use crate::shapes::SurfaceHit;

impl Scene {
    /// The lanes, where the scene has them and this CPU runs them: at most
    /// [`crate::accel::FLAT_MAX`] objects, every one of a kind the lanes test
    /// ([`crate::shapes::Shape::lane`]), none infinite or cut by its material.
    #[inline]
    pub fn object_lanes(&self) -> Option<&ObjectLanes> {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::avx2_features() {
            return self.lanes.as_ref();
        }
        None
    }

    /// The scene's object number of the lanes' slot `slot`.
    pub fn lane_object(&self, slot: u32) -> usize {
        self.bounded[slot as usize].object as usize
    }

    /// [`Scene::first_intersect`] with no bound of each ray of `rays` whose
    /// bit is set in `active`, into `hits` (the others are left as they are).
    /// A ray whose nearest hit ties between two objects walks the BVH, which
    /// decides as it always does.
    ///
    /// # Safety
    /// The CPU must have [`crate::cpu::AVX2_FEATURES`], and the scene lanes
    /// ([`Scene::object_lanes`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    pub unsafe fn closest_hits4(&self, rays: &[Ray; 4], active: u8, hits: &mut [Option<Hit>; 4]) {
        let Some(lanes) = self.lanes.as_ref() else { return };
        let nearest = lanes.closest(rays, f64::INFINITY, active);
        for (lane, ray) in rays.iter().enumerate() {
            let bit = 1 << lane;
            if active & bit == 0 {
                continue;
            }
            hits[lane] = if nearest.tie & bit != 0 {
                self.first_intersect_avx2(ray, f64::INFINITY)
            } else if nearest.hit & bit != 0 {
                let slot = nearest.slot[lane];
                let normal = lanes.shape(slot).normal(nearest.face[lane] as usize);
                let prim: &PrimRef = &self.bounded[slot as usize];
                Some(self.hit_record(ray, prim.object as usize, SurfaceHit::new(nearest.t[lane], normal)))
            } else {
                None
            };
        }
    }

    /// For each ray of `rays` whose bit is set in `active`: whether an opaque
    /// object other than object `ignore[lane]` (`u32::MAX` for none) lies on
    /// it over `(0, distance[lane])`, as a bit of the answer. In a scene whose
    /// every material blocks shadows, [`Scene::transmittance_to_surface`] is
    /// zero exactly where the bit is set.
    ///
    /// # Safety
    /// As [`Scene::closest_hits4`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    pub unsafe fn blocked4(&self, rays: &[Ray; 4], distance: &[f64; 4], ignore: &[u32; 4], active: u8) -> u8 {
        let Some(lanes) = self.lanes.as_ref() else { return 0 };
        lanes.blocked(rays, distance, ignore, active)
    }
}
