//! A row of Whitted pixels four at a time: the four camera rays are made as
//! one pixel's are, their first hits found together by the eye's buffer
//! (`scene/eye_lanes.rs`), and each pixel then traced on its own from its
//! hit, as [`Whitted::sample`] traces it. Every value is the one-pixel
//! loop's: the same camera rays, the same hits (the shared search answers
//! as the one-ray query does), the rest the same code.
//!
//! For rows whose pixels take one sample at the camera's pixel offset
//! through a pinhole (no lens, shutter or texture footprints) and scenes
//! that do not hide their emitters; other renders and a sample's trace
//! (`explain`) keep the one-pixel loop.

use std::mem::MaybeUninit;
use std::ops::Range;

use super::{camera_sample_from, NoTrace, Whitted};
use crate::film::PixelSum;
use crate::integrators::{add_sample, CameraSample, Integrator, RayCounts, View};
use crate::ray::Ray;

/// Whether [`row_avx2`] may render samples `samples` of `view`'s pixels.
#[inline]
pub(super) fn apply(view: &View, samples: &Range<u32>) -> bool {
    view.spp == 1
        && *samples == (0..1)
        && !view.lens
        && view.shutter.is_none()
        && !view.scene.uses_footprints()
        && !view.scene.settings.hide_emitters
}

/// [`Integrator::sample_row`] of `whitted` for pixels `x0..x0 + sums.len()`
/// of row `y`, where [`apply`] holds: the number of samples dropped.
///
/// # Safety
/// The CPU must have [`crate::cpu::AVX2_FEATURES`].
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
pub(super) unsafe fn row_avx2(whitted: &Whitted, view: &View, (x0, y): (u32, u32), counts: &mut RayCounts, sums: &mut [PixelSum]) -> u64 {
    let mut nonfinite = 0;
    let mut x = x0;
    let mut fours = sums.chunks_exact_mut(4);
    for four in &mut fours {
        // A single pinhole sample draws no value for its camera ray (`apply`).
        let mut cameras = [const { MaybeUninit::<CameraSample>::uninit() }; 4];
        let mut rays = [const { MaybeUninit::<Ray>::uninit() }; 4];
        for l in 0..4 {
            let camera = camera_sample_from(view, x + l as u32, y, 0, &mut || unreachable!("a pinhole's single sample draws no value"));
            // The camera (out of line, behind `dyn`) has just stored the ray
            // a coordinate at a time: read back with 32-byte loads, it stalled
            // on those stores, some 5 % of `luxo`'s time (issue 24).
            let ray = camera.ray.read_forwarded();
            rays[l].write(ray);
            cameras[l].write(CameraSample { ray, ..camera });
        }
        // SAFETY: the loop above wrote all four.
        let rays: &[Ray; 4] = &*rays.as_ptr().cast();
        let mut hits = [None, None, None, None];
        view.scene.first_hits_from_eye(rays, &mut hits);
        for (l, sum) in four.iter_mut().enumerate() {
            // SAFETY: written above.
            let camera = cameras[l].assume_init_ref();
            let value = whitted.sample_known(view, (x + l as u32, y, 0), Some((camera, &mut hits[l])), counts, &mut NoTrace);
            nonfinite += add_sample(sum, value, view.clamp);
        }
        x += 4;
    }
    for sum in fours.into_remainder() {
        nonfinite += add_sample(sum, whitted.sample(view, x, y, 0, counts), view.clamp);
        x += 1;
    }
    nonfinite
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective};
    use crate::integrators::sample_row_one_by_one;
    use crate::lights::PointLight;
    use crate::materials::{Material, Reflection};
    use crate::math::{Mat4, Rgb, Vec3};
    use crate::scene::{Scene, SceneBuilder};
    use crate::shapes::{Cuboid, Quadric, Rectangle, Sphere};

    /// Balls of plastic, mirror and glass, an ellipsoid and a box on a floor,
    /// under two point lights: reflected, refracted and shadow rays behind
    /// every camera ray.
    fn gallery() -> Scene {
        let camera = Perspective::look_at(Vec3::new(0.3, 4.0, 9.0), Vec3::new(0.0, 0.5, 0.0), Vec3::Y, Fov::VerticalDeg(45.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let floor = b.material(Material::plastic(Rgb::new(0.7, 0.6, 0.5), 0.1, 0.8, 0.2, 20.0)).unwrap();
        let mirror = b.material(Material { reflection: Reflection::Constant(Rgb::splat(0.8)), ..Material::default() }).unwrap();
        let glass = b.material(Material::glass(1.5, 0.8, 300.0)).unwrap();
        let plastic = b.material(Material::plastic(Rgb::new(0.2, 0.4, 0.8), 0.1, 0.7, 0.5, 40.0)).unwrap();
        b.object(Rectangle::horizontal(0.0, -6.0, 6.0, -6.0, 6.0).unwrap(), floor).unwrap();
        let mut rng = crate::sampling::Rng::for_sample(8, 0, 0);
        let mut rand = move || rng.uniform();
        for k in 0..24 {
            let r = 0.2 + 0.4 * rand();
            let centre = Vec3::new(rand() * 8.0 - 4.0, r, rand() * 8.0 - 4.0);
            b.object(Sphere::new(centre, r).unwrap(), [plastic, mirror, glass][k % 3]).unwrap();
        }
        b.object(Quadric::ellipsoid(Vec3::new(0.0, 0.6, 1.0), Vec3::new(0.8, 0.5, 0.6)).unwrap(), glass).unwrap();
        let turn = Mat4::from_translation(Vec3::new(-1.5, 0.4, 1.5)) * Mat4::from_rotation_y(0.4);
        b.object(Cuboid::new(-Vec3::splat(0.4), Vec3::splat(0.4), turn).unwrap(), plastic).unwrap();
        b.light(PointLight::new(Vec3::new(-4.0, 6.0, 5.0), Rgb::splat(40.0)).unwrap());
        b.light(PointLight::new(Vec3::new(5.0, 4.0, -3.0), Rgb::new(10.0, 12.0, 14.0)).unwrap());
        b.build().unwrap()
    }

    /// Rows four pixels at a time and one at a time, whole and in windows
    /// whose widths leave a remainder: the same sums, bit for bit, and the
    /// same ray counts.
    #[test]
    fn rows_four_at_a_time_add_the_same_sums() {
        if !crate::cpu::avx2_features() {
            eprintln!("skipped: this CPU lacks AVX2, and the packets run only there");
            return;
        }
        let scene = gallery();
        let whitted = Whitted::new(&scene, 5, 0.0);
        let (width, height) = (48, 27);
        let camera = scene.settings.camera.for_image(width, height).unwrap();
        let view = View::new(&scene, &*camera, width, height, 1, 3);
        assert!(apply(&view, &(0..1)), "the packets should run");
        let mut secondary = 0;
        for y in 0..height {
            for (x0, w) in [(0, width as usize), (5, 11), (45, 3)] {
                let (mut four, mut one) = (RayCounts::default(), RayCounts::default());
                let mut sums = vec![PixelSum::default(); w];
                let mut expected = sums.clone();
                let dropped = whitted.sample_row(&view, (x0, y), 0..1, &mut four, &mut sums);
                let expected_dropped = sample_row_one_by_one(&whitted, &view, (x0, y), 0..1, &mut one, &mut expected);
                assert_eq!(dropped, expected_dropped);
                assert_eq!((four.camera, four.secondary, four.shadow), (one.camera, one.secondary, one.shadow));
                let bits = |s: &[PixelSum]| s.iter().map(|p| p.sum.to_array().map(f64::to_bits)).collect::<Vec<_>>();
                assert_eq!(bits(&sums), bits(&expected), "row {y} from {x0}");
                secondary += one.secondary;
            }
        }
        assert!(secondary > 500, "only {secondary} secondary rays");
    }

    /// Several samples a pixel, or a hidden emitter, keep the one-pixel loop.
    #[test]
    fn other_renders_keep_one_pixel_at_a_time() {
        let mut scene = gallery();
        let camera = scene.settings.camera.for_image(8, 8).unwrap();
        assert!(!apply(&View::new(&scene, &*camera, 8, 8, 4, 1), &(0..4)), "four samples");
        assert!(!apply(&View::new(&scene, &*camera, 8, 8, 1, 1), &(1..2)), "a later pass");
        scene.settings.hide_emitters = true;
        assert!(!apply(&View::new(&scene, &*camera, 8, 8, 1, 1), &(0..1)), "hide_emitters");
    }
}
