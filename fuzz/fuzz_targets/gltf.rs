//! Fuzz target: any bytes read as a .gltf file must give Ok or a LoadError, never a panic, hang or huge allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    // A folder that does not exist: referenced files (.mtl, .bin) are reported missing, never read.
    let _ = lamplight_scene::import::load_bytes(Path::new("/nonexistent-lamplight-fuzz/input.gltf"), data);
    // The same bytes behind a GLB header, so the binary container is explored too.
    let mut glb = b"glTF\x02\0\0\0".to_vec();
    glb.extend_from_slice(data);
    let _ = lamplight_scene::import::load_bytes(Path::new("/nonexistent-lamplight-fuzz/input.glb"), &glb);
});
