//! Convergence of the path tracer on the Cornell box: the RMSE against a
//! high-sample reference falls as `1 / sqrt(spp)` (slope -1/2 in log-log) or
//! faster: the scrambled Sobol points stratify the pixel area and the first
//! bounces, which measured a slope of -0.87 at 12x12 (4 to 256 spp against 4096).
//! The test asks for a slope between -1.1 and -0.4: never slower than Monte Carlo.

use lamplight_core::film::Image;
use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::builtin;

use crate::common::rmse;

fn cornell(size: u32, spp: u32, seed: u64) -> Image {
    let scene = (builtin::find("cornell-box").unwrap().build)().unwrap();
    let options = RenderOptions {
        width: size,
        height: size,
        spp,
        seed,
        integrator: lamplight_core::integrators::find("path").unwrap(),
        ..RenderOptions::default()
    };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0
}

#[test]
fn rmse_falls_as_one_over_sqrt_spp() {
    let size = 12;
    // Another seed than the estimates, so that the reference shares no samples with them.
    let reference = cornell(size, 4096, 99);
    let counts = [4u32, 16, 64, 256];
    let errors: Vec<f64> = counts.iter().map(|&spp| rmse(&cornell(size, spp, 1), &reference)).collect();
    // Least-squares slope of log(RMSE) against log(spp).
    let xs: Vec<f64> = counts.iter().map(|&n| (n as f64).ln()).collect();
    let ys: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / 4.0, ys.iter().sum::<f64>() / 4.0);
    let slope = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum::<f64>() / xs.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
    eprintln!("RMSE {errors:?}, slope {slope:.3}");
    assert!((-1.1..=-0.4).contains(&slope), "slope {slope}, errors {errors:?}");
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
}
