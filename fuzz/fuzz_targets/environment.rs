//! Fuzz target: any bytes read as an environment map (.exr when the first byte is even, .hdr when odd) must give an image
//! of finite non-negative pixels or an ImageError, never a panic, hang or huge allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Some((&selector, bytes)) = data.split_first() else { return };
    let path = if selector % 2 == 0 { Path::new("sky.exr") } else { Path::new("sky.hdr") };
    if let Ok(image) = lamplight_scene::env_map::decode_environment(path, bytes) {
        assert!(image.pixels.iter().flatten().all(|c| c.is_finite() && *c >= 0.0));
    }
});
