//! Smooth mirror reflection whose reflectance is a Fresnel term: a conductor of
//! complex index `eta + i k` per channel, a dielectric coating rescaled to
//! `[min, max]` (the lecture's `reflection {min, max fresnel}`), or a constant
//! weight. The lobe is a delta: `wi` is the mirror direction and the sample
//! weight `f cos / pdf` is the reflectance itself, which never exceeds 1 for a
//! conductor (Fresnel reflectance lies in `[0, 1]`).

use super::dielectric::reflect_local;
use super::fresnel::{fresnel_conductor, fresnel_dielectric};
use super::{Lobe, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// Where a mirror's reflectance comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MirrorFresnel {
    /// A constant per-channel weight.
    Constant(Rgb),
    /// Dielectric Fresnel of relative index `eta`, rescaled to `min + (max - min) F`.
    Dielectric {
        /// `n_t / n_i` across the boundary.
        eta: f64,
        /// Reflectance at `F = 0`.
        min: f64,
        /// Reflectance at `F = 1`.
        max: f64,
    },
    /// Conductor Fresnel with complex index `eta + i k`.
    Conductor {
        /// Real part of the index, per channel.
        eta: Rgb,
        /// Extinction coefficient, per channel.
        k: Rgb,
    },
}

impl MirrorFresnel {
    /// Reflectance at incidence cosine `cos_i`.
    pub fn reflectance(&self, cos_i: f64) -> Rgb {
        match *self {
            MirrorFresnel::Constant(w) => w,
            MirrorFresnel::Dielectric { eta, min, max } => Rgb::splat((min + (max - min) * fresnel_dielectric(cos_i, eta)).max(0.0)),
            MirrorFresnel::Conductor { eta, k } => fresnel_conductor(cos_i, eta, k),
        }
    }
}

/// A smooth mirror (delta): the mirror direction, weighted by the reflectance.
impl Scatter for MirrorFresnel {
    const DELTA: bool = true;

    /// An upper bound of the reflectance over all angles.
    fn bound(&self) -> Rgb {
        match *self {
            MirrorFresnel::Constant(w) => w,
            MirrorFresnel::Dielectric { min, max, .. } => Rgb::splat(min.max(max).max(0.0)),
            MirrorFresnel::Conductor { .. } => Rgb::ONE,
        }
    }

    /// A constant weight scales; a Fresnel-driven mirror keeps its physics
    /// unscaled and becomes a constant-weight tint otherwise.
    fn scaled(self, s: Rgb) -> Lobe {
        match self {
            MirrorFresnel::Constant(w) => MirrorFresnel::Constant(w * s).into(),
            m if s == Rgb::ONE => m.into(),
            m => MirrorFresnel::Constant(m.bound() * s).into(),
        }
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u_choice: f64, _u: (f64, f64)) -> Option<Sampled> {
        Some(Sampled::Delta { wi: reflect_local(wo), weight: self.reflectance(wo.z), eta: 1.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdfs::Metal;

    #[test]
    fn conductor_reflectance_stays_in_unit_range_and_rises_to_one_at_grazing() {
        for metal in [Metal::Gold, Metal::Silver, Metal::Copper, Metal::Aluminium] {
            let (eta, k) = metal.eta_k();
            let m = MirrorFresnel::Conductor { eta, k };
            for i in 0..=100 {
                let r = m.reflectance(i as f64 / 100.0);
                assert!(r.min_element() >= 0.0 && r.max_element() <= 1.0, "{metal:?}: {r}");
            }
            assert!(m.reflectance(0.0).min_element() > 0.999);
        }
    }
}
