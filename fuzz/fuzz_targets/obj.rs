//! Fuzz target: any bytes read as a .obj file must give Ok or a LoadError, never a panic, hang or huge allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    // A folder that does not exist: referenced files (.mtl, .bin) are reported missing, never read.
    let _ = lamplight_scene::import::load_bytes(Path::new("/nonexistent-lamplight-fuzz/input.obj"), data);
});
