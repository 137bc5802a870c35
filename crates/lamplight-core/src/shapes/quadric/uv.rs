//! Surface coordinates of the named quadrics, all surfaces of revolution in a
//! local frame `l = W^-1 p` whose `z` axis is their axis
//! ([`crate::shapes::surface::revolution`]): `u = phi / (2 pi)` around the
//! axis, and `v`
//!
//! | quadric | local frame `W` | `v` |
//! |---|---|---|
//! | ellipsoid | centre, semi-axes scaled to the unit sphere | `(pi - theta) / pi`: 0 at the `-z` end, 1 at `+z` (pbrt's sphere) |
//! | cylinder, cone, paraboloid, hyperboloid | axis point (apex, centre), unit axis | distance along the axis, scene units |
//! | cylinder, cone segment; paraboloid cup | as above | the fraction of the segment, `[0, 1]` from `from` (apex) to `to` (base, rim) |
//!
//! The azimuth starts at the first vector of [`crate::math::orthonormal_basis`]
//! of the axis. A quadric given by its matrix has no axis and gets
//! `(0, 0)` with a frame around the normal.

use crate::math::{orthonormal_basis, Mat4, Vec3};
use crate::shapes::surface::{revolution, Meridian};
use crate::shapes::SurfaceCoords;

/// A quadric's local frame of revolution and what its `v` measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Revolution {
    world_from_local: Mat4,
    local_from_world: Mat4,
    meridian: Meridian,
}

impl Revolution {
    /// The frame at `origin` with `z` along `axis * axial` and `x`, `y` across it
    /// scaled by `radial` (`axis` unit).
    pub fn around(origin: Vec3, axis: Vec3, radial: f64, axial: f64, meridian: Meridian) -> Revolution {
        let (x, y) = orthonormal_basis(axis);
        Revolution::new(
            Mat4::from_cols((x * radial).extend(0.0), (y * radial).extend(0.0), (axis * axial).extend(0.0), origin.extend(1.0)),
            meridian,
        )
    }

    /// The frame `world_from_local` (affine, invertible).
    pub fn new(world_from_local: Mat4, meridian: Meridian) -> Revolution {
        Revolution { world_from_local, local_from_world: world_from_local.inverse(), meridian }
    }

    /// The frame moved by the affine `m`.
    pub fn transformed(&self, m: &Mat4) -> Revolution {
        Revolution::new(*m * self.world_from_local, self.meridian)
    }

    /// The coordinates at world point `p` with outward normal `n`.
    pub fn coords(&self, p: Vec3, n: Vec3) -> SurfaceCoords {
        let q = self.local_from_world.transform_point3(p);
        // Normals map to the local frame by (W^-1)^-T = W^T.
        let local_n = self.world_from_local.transpose().transform_vector3(n).normalize_or_zero();
        match revolution(q, local_n, self.meridian) {
            Some(c) => c.transformed(&self.world_from_local),
            None => SurfaceCoords::unparametrized(n),
        }
    }
}
