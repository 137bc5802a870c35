//! Ray cones (Akenine-Moeller et al. 2019): how wide a camera ray's pixel
//! footprint is along its path, which picks a texture's mip level. Both
//! integrators carry one, so it lives with the sampling they share rather than
//! in either of them.

use crate::ray::Ray;

/// A camera ray's pixel footprint, a cone (ray cones, Akenine-Moeller et al.
/// 2019): at distance `t` along the path it is `width + spread t` wide. Mirror
/// and refracted rays continue the cone from the width at their hit (surface
/// curvature is not followed). Made only for scenes with trilinear textures.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Cone {
    /// Width at the camera.
    pub width: f64,
    /// Growth per unit of distance.
    pub spread: f64,
}

impl Cone {
    /// The footprint of the camera ray `ray`, from the rays `x` and `y` one pixel
    /// over in x and y: the distance to them (their larger), narrowed by
    /// `1 / sqrt(spp)` down to 1/8 for supersampled pixels (pbrt-v4's
    /// `Approximate_dp_dxy` scaling):
    /// `width = max(|o_x - o|, |o_y - o|) s`, `spread = max(|d_x - d|, |d_y - d|) s`,
    /// `s = max(1 / sqrt(spp), 1/8)`.
    #[inline]
    pub fn of_neighbours(ray: &Ray, x: &Ray, y: &Ray, spp: u32) -> Cone {
        let width = (x.origin - ray.origin).length().max((y.origin - ray.origin).length());
        let spread = (x.dir - ray.dir).length().max((y.dir - ray.dir).length());
        let scale = (1.0 / f64::from(spp.max(1)).sqrt()).max(0.125);
        Cone { width: width * scale, spread: spread * scale }
    }
}
