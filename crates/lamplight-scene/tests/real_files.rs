//! Every real file of `../shared/data` loads and renders a sensible image: the
//! model is framed (it covers a good part of the image, not all of it), lit (not
//! black), not blown out (not a white glow), and no sample is NaN or infinite.
//! Skips with a message when the folder is absent.

use crate::common;

use common::shared_data;
use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::imported;

const FILES: &[&str] = &[
    "meshes/stanford-bunny.obj",
    "meshes/igea.ply",
    "meshes/igea-1m.ply",
    "meshes/cornell-box/CornellBox-Original.obj",
    "gltf/Box/Box.gltf",
    "gltf/BoxTextured.glb",
    "gltf/Duck.glb",
    "gltf/DamagedHelmet.glb",
    "gltf/Suzanne/Suzanne.gltf",
];

#[test]
fn every_shared_file_renders_a_sensible_image() {
    let Some(data) = shared_data("every_shared_file_renders_a_sensible_image") else { return };
    for file in FILES {
        let path = data.join(file);
        let scene = imported::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let options = RenderOptions { width: 48, height: 48, ..RenderOptions::default() };
        let (image, stats) = render_image(&scene, &options, &RenderControl::default()).unwrap();
        assert_eq!(stats.nonfinite_samples, 0, "{file}: NaN or infinite samples");
        let background = scene.settings.background.as_vec3().to_array();
        let covered: Vec<[f32; 3]> =
            image.pixels.iter().copied().filter(|p| p.iter().zip(background).any(|(a, b)| (*a - b).abs() > 1e-6)).collect();
        let fraction = covered.len() as f64 / image.pixels.len() as f64;
        assert!((0.05..0.995).contains(&fraction), "{file}: the model covers {:.1} % of the image", 100.0 * fraction);
        let lit = covered.iter().filter(|p| p.iter().any(|&c| c > 0.02)).count();
        assert!(lit * 2 > covered.len(), "{file}: most of the model is black");
        let white = covered.iter().filter(|p| p.iter().all(|&c| c >= 1.0)).count();
        assert!(white * 2 < covered.len(), "{file}: most of the model is blown out to white");
    }
}
