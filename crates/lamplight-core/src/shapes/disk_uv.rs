//! How a [`super::Disk`]'s surface coordinates are laid out (`disk` `uv_layout`).
//!
//! | layout | `(u, v)` at a point `x t + y b` from the centre, `r = hypot(x, y)` | `dp/du`, `dp/dv` |
//! |---|---|---|
//! | `polar` (default) | pbrt-v4's: `u = phi / (2 pi)`, `v = 1 - r / R`, `phi = atan2(y, x)` in the frame [`crate::math::orthonormal_basis`] builds around the (world) normal | `2 pi (-y t + x b)`, `-R (p - c) / r` |
//! | `radial` | Mitsuba 3's disk with lamplight's `v` (`v = 1 - v_mitsuba`, as for every Mitsuba texture coordinate): `u = r / R`, `v = 1 - phi / (2 pi)`, in the frame of the disk as given (the basis around its own normal), carried by its matrix | `R (p - c) / r`, `-2 pi (-y t + x b)` |
//!
//! `radial` exists for Mitsuba scenes: Mitsuba's disk has `uv = (r, phi / 2 pi)`
//! in its local frame (measured with Mitsuba 3.9.1: the unit disk hit at `(0.3,
//! 0.5)` has `uv = (0.5831, 0.1640)`), so a texture on it follows the local `x`
//! axis as `to_world` turns it; `polar` re-derives its frame from the world
//! normal and forgets the turn.

use super::surface::{azimuth, SurfaceCoords};
use crate::math::Vec3;

/// The layout of a disk's `(u, v)` (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DiskUv {
    /// pbrt-v4's polar coordinates in the world normal's frame.
    Polar,
    /// Mitsuba's radial coordinates in the frame `(x, y)` (unit, in the disk's plane).
    Radial {
        /// Where `phi = 0`.
        x: Vec3,
        /// Where `phi = pi / 2`.
        y: Vec3,
    },
}

impl DiskUv {
    /// The coordinates of the point `d` from the centre of a disk of radius
    /// `radius` (`t`, `b`: the polar layout's frame; `n`: the normal, for the
    /// centre, where the angle is undefined).
    pub(super) fn coords(self, d: Vec3, radius: f64, t: Vec3, b: Vec3, n: Vec3) -> SurfaceCoords {
        let (t, b) = match self {
            DiskUv::Polar => (t, b),
            DiskUv::Radial { x, y } => (x, y),
        };
        let (x, y) = (d.dot(t), d.dot(b));
        let r = x.hypot(y);
        if !(r > 0.0) {
            // The centre: Mitsuba's (0, 0), pbrt's (0, 1); both have v = 1 in lamplight's.
            return SurfaceCoords { uv: [0.0, 1.0], ..SurfaceCoords::unparametrized(n) };
        }
        let tau = std::f64::consts::TAU;
        let around = (b * x - t * y) * tau;
        let outward = (t * x + b * y) * (radius / r);
        match self {
            DiskUv::Polar => SurfaceCoords::new([azimuth(x, y) / tau, (1.0 - r / radius).max(0.0)], around, -outward),
            DiskUv::Radial { .. } => SurfaceCoords::new([(r / radius).min(1.0), 1.0 - azimuth(x, y) / tau], outward, -around),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radial_layout_is_mitsubas_with_v_flipped() {
        // Mitsuba 3.9.1's unit disk, hit from +z: (0.3, 0.5) -> uv (0.583095, 0.163989),
        // (0.5, -0.2) -> (0.538517, 0.939441).
        let layout = DiskUv::Radial { x: Vec3::X, y: Vec3::Y };
        for (p, mitsuba) in [(Vec3::new(0.3, 0.5, 0.0), [0.583095, 0.163989]), (Vec3::new(0.5, -0.2, 0.0), [0.538517, 0.939441])] {
            let c = layout.coords(p, 1.0, Vec3::X, Vec3::Y, Vec3::Z);
            assert!((c.uv[0] - mitsuba[0]).abs() < 1e-6 && (c.uv[1] - (1.0 - mitsuba[1])).abs() < 1e-6, "{p}: {:?}", c.uv);
        }
        // A disk of radius 2 turned by 90 degrees: phi is measured from its turned x axis.
        let turned = DiskUv::Radial { x: Vec3::Y, y: -Vec3::X };
        let c = turned.coords(Vec3::new(0.0, 1.0, 0.0), 2.0, Vec3::X, Vec3::Y, Vec3::Z);
        assert_eq!(c.uv, [0.5, 1.0]);
        assert_eq!(layout.coords(Vec3::ZERO, 1.0, Vec3::X, Vec3::Y, Vec3::Z).uv, [0.0, 1.0]);
    }

    #[test]
    fn radial_tangents_are_the_derivatives_of_the_point() {
        let (x, y, radius) = (Vec3::new(0.6, 0.8, 0.0), Vec3::new(-0.8, 0.6, 0.0), 1.5);
        let layout = DiskUv::Radial { x, y };
        let at = |u: f64, v: f64| {
            let phi = (1.0 - v) * std::f64::consts::TAU;
            (x * phi.cos() + y * phi.sin()) * (u * radius)
        };
        for (u, v) in [(0.2, 0.3), (0.9, 0.75)] {
            let c = layout.coords(at(u, v), radius, Vec3::X, Vec3::Y, Vec3::Z);
            assert!((c.uv[0] - u).abs() < 1e-12 && (c.uv[1] - v).abs() < 1e-12, "{:?}", c.uv);
            let h = 1e-6;
            for (analytic, numeric) in
                [(c.dpdu, (at(u + h, v) - at(u - h, v)) / (2.0 * h)), (c.dpdv, (at(u, v + h) - at(u, v - h)) / (2.0 * h))]
            {
                assert!((analytic - numeric).length() < 1e-6, "{analytic} vs {numeric}");
            }
        }
    }
}
