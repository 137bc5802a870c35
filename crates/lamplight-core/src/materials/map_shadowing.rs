//! What a normal or bump map leaves of the surface it turns, as Mitsuba 3's
//! `normalmap` and `bumpmap` keep it: the side of the unmapped shading normal,
//! and a shadowing term for the mapped one.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `map_shadowing` | boolean | false | dims light that arrives low over the unmapped surface by Estevez et al.'s microfacet shadowing term (Mitsuba's `use_shadowing_function`, on in Mitsuba) |
//!
//! A map turns the shading normal from `n` (the unmapped one) to `n'`. The
//! path tracer then evaluates the BSDF about `n'`, and in addition:
//!
//! - under [`crate::scene::Sides::Shading`] (Mitsuba's sides) a direction
//!   counts only where it lies on the same side of `n` as of `n'` (Mitsuba's
//!   `cos_theta(wo) * cos_theta(perturbed_wo) > 0`): light from below the
//!   unmapped surface does not reach it through a tilted normal. Under
//!   [`crate::scene::Sides::Geometric`] the geometric normal already decides.
//! - with `map_shadowing`, the BSDF's value towards the light `wi` is
//!   multiplied by `G = 2 / (1 + sqrt(1 + a^2 tan^2(theta_i)))`, with `theta_i`
//!   the angle of `wi` to `n` and `a^2 = min(tan^2(theta') / 8, 1)`, `theta'`
//!   the angle from `n` to `n'` ("A Microfacet-Based Shadowing Function to Solve
//!   the Bump Terminator Problem", Estevez, Barla and Pharr, Ray Tracing Gems,
//!   2019; Mitsuba's `eval_shadow_terminator`). The mapped normal stands for
//!   microfacets whose slopes have that spread; `G` is their Smith masking of
//!   `wi`: 1 overhead, 0 at grazing light, and 1 everywhere on an unmapped point.
//!   It hides the hard terminator a tilted normal draws on a lit sphere.

use crate::math::Vec3;
use crate::params::{Param, ParamResult, ParamType as T, Params};

/// The `map_shadowing` row of every surface kind.
pub const MAP_SHADOWING_PARAM: Param = Param::new(
    "map_shadowing",
    T::Bool,
    "false",
    "",
    "with a normal or bump map: Mitsuba's shadowing term (Estevez et al. 2019), which dims light arriving low over the unmapped surface",
);

/// Reads [`MAP_SHADOWING_PARAM`].
pub fn read(p: &mut Params<'_>) -> ParamResult<bool> {
    Ok(p.boolean("map_shadowing")?.unwrap_or(false))
}

/// A shading point whose normal a map turned: the unmapped normal `n` and, with
/// `map_shadowing`, the term's `a^2` (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perturbed {
    /// The unmapped shading normal (unit, on the ray's side).
    pub unmapped: Vec3,
    /// `a^2 = min(tan^2(theta') / 8, 1)`, or 0 without the shadowing term.
    alpha2: f64,
}

impl Perturbed {
    /// The turn from the unit normal `unmapped` to the unit normal `mapped`;
    /// `shadowing` switches the term on.
    pub fn new(unmapped: Vec3, mapped: Vec3, shadowing: bool) -> Perturbed {
        let alpha2 = if shadowing { (0.125 * tan2(mapped.dot(unmapped))).min(1.0) } else { 0.0 };
        Perturbed { unmapped, alpha2 }
    }

    /// Whether the unit direction `wi` lies on the side of the unmapped normal
    /// that `mapped_side` (its side of the mapped normal) says.
    #[inline]
    pub fn same_side(&self, wi: Vec3, mapped_side: bool) -> bool {
        (wi.dot(self.unmapped) > 0.0) == mapped_side
    }

    /// What the BSDF's value towards the unit direction `wi` is multiplied by:
    /// 0 where `check_side` and `wi` lies on another side of the unmapped
    /// normal than `mapped_side` (its side of the mapped one), else
    /// [`Perturbed::shadowing`].
    #[inline]
    pub fn weight(&self, wi: Vec3, mapped_side: bool, check_side: bool) -> f64 {
        if check_side && !self.same_side(wi, mapped_side) {
            0.0
        } else {
            self.shadowing(wi)
        }
    }

    /// The shadowing term `G` of light arriving along the unit direction `wi`.
    #[inline]
    pub fn shadowing(&self, wi: Vec3) -> f64 {
        if self.alpha2 == 0.0 {
            return 1.0;
        }
        // tan^2 is infinite at grazing light: G is then 0, never NaN (alpha2 > 0).
        2.0 / (1.0 + (1.0 + self.alpha2 * tan2(wi.dot(self.unmapped))).sqrt())
    }
}

/// `tan^2` of the angle whose cosine is `cos` (any sign; infinite at 0).
fn tan2(cos: f64) -> f64 {
    let c2 = cos * cos;
    (1.0 - c2).max(0.0) / c2
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_term_is_one_overhead_and_without_a_turn_and_falls_to_zero_at_grazing_light() {
        let n = Vec3::Z;
        let tilted = Vec3::new(0.5, 0.0, 1.0).normalize();
        let p = Perturbed::new(n, tilted, true);
        assert_eq!(p.shadowing(n), 1.0);
        assert_eq!(p.shadowing(Vec3::X), 0.0);
        assert_eq!(Perturbed::new(n, n, true).shadowing(Vec3::new(1.0, 0.0, 0.1).normalize()), 1.0);
        assert_eq!(Perturbed::new(n, tilted, false).shadowing(Vec3::new(1.0, 0.0, 0.1).normalize()), 1.0);
        // tan^2(theta') = 0.25: a^2 = 1/32; light at 60 degrees, tan^2 = 3.
        let wi = Vec3::new(3f64.sqrt() / 2.0, 0.0, 0.5);
        let want = 2.0 / (1.0 + (1.0 + 3.0 / 32.0f64).sqrt());
        assert!((p.shadowing(wi) - want).abs() < 1e-12, "{} vs {want}", p.shadowing(wi));
        // Below the surface as above it, and a^2 capped at 1 for steep turns.
        assert!((p.shadowing(Vec3::new(wi.x, 0.0, -wi.z)) - want).abs() < 1e-12);
        let steep = Perturbed::new(n, Vec3::new(10.0, 0.0, 1.0).normalize(), true);
        // a^2 = 1, tan^2 = 3: 2 / (1 + sqrt(4)).
        assert!((steep.shadowing(wi) - 2.0 / 3.0).abs() < 1e-12, "{}", steep.shadowing(wi));
    }

    #[test]
    fn a_direction_counts_on_the_same_side_of_both_normals() {
        let p = Perturbed::new(Vec3::Z, Vec3::new(0.6, 0.0, 0.8), false);
        // Below the unmapped surface, above the mapped one: not the same side.
        let low = Vec3::new(1.0, 0.0, -0.1).normalize();
        assert!(!p.same_side(low, low.dot(Vec3::new(0.6, 0.0, 0.8)) > 0.0));
        let high = Vec3::new(0.2, 0.0, 1.0).normalize();
        assert!(p.same_side(high, true));
        assert!(!p.same_side(high, false));
    }
}
