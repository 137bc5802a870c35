//! How a [`super::Cuboid`]'s surface coordinates are laid out (`box` `uv_layout`).
//!
//! With `f_k = (l_k - min_k) / (max_k - min_k)` the fractions of the local point
//! `l`, and `E_k = M e_k (max_k - min_k)` the box's world edges:
//!
//! | layout | face of axis `i`, `(a, b) = (i + 1, i + 2) mod 3` | `dp/du` |
//! |---|---|---|
//! | `faces` (default) | `(f_a, f_b)` on the `max` face, `(1 - f_a, f_b)` on the `min` face: `dp/du x dp/dv` points out on all six | `+-E_a` |
//! | `mitsuba` | the texture coordinates of Mitsuba 3's `cube` mesh, with lamplight's `v = 1 - v_mitsuba` (table below) | below |
//!
//! Mitsuba's `cube` is a mesh whose faces each map `[0, 1]^2` (its
//! `src/shapes/cube.cpp`: four vertices a face at `uv` `(0, 1), (1, 1), (1, 0),
//! (0, 0)`); per face, Mitsuba's `(u, v)` and so `dp/du`:
//!
//! | face | `u` | `v_mitsuba` | `dp/du` |
//! |---|---|---|---|
//! | `+x` | `f_y` | `1 - f_z` | `+E_y` |
//! | `-x` | `f_y` | `f_z` | `+E_y` |
//! | `+y` | `1 - f_x` | `1 - f_z` | `-E_x` |
//! | `-y` | `f_z` | `f_x` | `+E_z` |
//! | `+z` | `f_y` | `f_x` | `+E_y` |
//! | `-z` | `1 - f_y` | `f_x` | `-E_y` |
//!
//! The `faces` layout's `dp/du` runs along another edge on `+y` and `+-z`, so an
//! anisotropic BSDF on a Mitsuba `cube` needs this layout to be Mitsuba's
//! (`roughconductor_aniso_cube` in `bench/mitsuba_xml/cases_aniso.py`), and so
//! does a texture.

use glam::DMat3;

use super::surface::SurfaceCoords;
use crate::math::Vec3;

/// The layout of a box's `(u, v)` (module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BoxUv {
    /// Each face `[0, 1]^2` with `dp/du x dp/dv` outward.
    #[default]
    Faces,
    /// Mitsuba's `cube` mesh.
    Mitsuba,
}

/// Per face (+x, -x, +y, -y, +z, -z): `u`'s axis and direction, then Mitsuba's `v`'s.
const MITSUBA: [((usize, bool), (usize, bool)); 6] = [
    ((1, true), (2, false)),
    ((1, true), (2, true)),
    ((0, false), (2, false)),
    ((2, true), (0, true)),
    ((1, true), (0, true)),
    ((1, false), (0, true)),
];

impl BoxUv {
    /// The coordinates on the face of `axis` (`max_side`: the `max` face) at the
    /// fractions `f` (each clamped to `[0, 1]`), for the box's linear map
    /// `linear` and local `size`.
    pub(super) fn coords(self, axis: usize, max_side: bool, f: Vec3, linear: DMat3, size: Vec3) -> SurfaceCoords {
        let edge = |k: usize| linear.col(k) * size[k];
        match self {
            BoxUv::Faces => {
                let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                let (fa, fb) = (f[a].clamp(0.0, 1.0), f[b].clamp(0.0, 1.0));
                if max_side {
                    SurfaceCoords::new([fa, fb], edge(a), edge(b))
                } else {
                    SurfaceCoords::new([1.0 - fa, fb], -edge(a), edge(b))
                }
            }
            BoxUv::Mitsuba => {
                let ((ua, up), (va, vp)) = MITSUBA[2 * axis + usize::from(!max_side)];
                let along = |k: usize, plus: bool| {
                    let x = f[k].clamp(0.0, 1.0);
                    if plus {
                        (x, edge(k))
                    } else {
                        (1.0 - x, -edge(k))
                    }
                };
                let ((u, dpdu), (v_mitsuba, dpdv_mitsuba)) = (along(ua, up), along(va, vp));
                SurfaceCoords::new([u, 1.0 - v_mitsuba], dpdu, -dpdv_mitsuba)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mitsuba's cube (`src/shapes/cube.cpp`): per face its four vertices, at
    /// `uv` (0, 1), (1, 1), (1, 0), (0, 0), and its outward axis.
    const FACES: [([[f64; 3]; 4], usize, bool); 6] = [
        ([[1., -1., -1.], [1., -1., 1.], [-1., -1., 1.], [-1., -1., -1.]], 1, false),
        ([[1., 1., -1.], [-1., 1., -1.], [-1., 1., 1.], [1., 1., 1.]], 1, true),
        ([[1., -1., -1.], [1., 1., -1.], [1., 1., 1.], [1., -1., 1.]], 0, true),
        ([[1., -1., 1.], [1., 1., 1.], [-1., 1., 1.], [-1., -1., 1.]], 2, true),
        ([[-1., -1., 1.], [-1., 1., 1.], [-1., 1., -1.], [-1., -1., -1.]], 0, false),
        ([[1., 1., -1.], [1., -1., -1.], [-1., -1., -1.], [-1., 1., -1.]], 2, false),
    ];

    #[test]
    fn the_mitsuba_layout_is_the_cube_meshs_bilinear_map() {
        // On each face p(u, v) = v3 + u (v2 - v3) + v_m (v0 - v3): at a few (u, v_m)
        // the layout gives back (u, 1 - v_m) and the tangents v2 - v3, -(v0 - v3),
        // for the unit cube [-1, 1]^3 (size 2, linear the identity).
        for (corners, axis, max_side) in FACES {
            let [v0, _, v2, v3] = corners.map(Vec3::from_array);
            for (u, vm) in [(0.25, 0.5), (0.8, 0.1), (0.5, 0.9)] {
                let p = v3 + (v2 - v3) * u + (v0 - v3) * vm;
                let c = BoxUv::Mitsuba.coords(axis, max_side, (p + Vec3::ONE) / 2.0, DMat3::IDENTITY, Vec3::splat(2.0));
                assert!((c.uv[0] - u).abs() < 1e-12 && (c.uv[1] - (1.0 - vm)).abs() < 1e-12, "{corners:?} ({u}, {vm}): {:?}", c.uv);
                assert!((c.dpdu - (v2 - v3)).length() < 1e-12 && (c.dpdv + (v0 - v3)).length() < 1e-12, "{corners:?}: {c:?}");
            }
        }
    }
}
