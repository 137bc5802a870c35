//! Fuzz target: any bytes read as a .npy file must give an array or an NpyError, never a panic, hang or huge allocation;
//! an array that is read must also convert to (N, 3) rows, or fail, without a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("input.npy");
    if let Ok(array) = lamplight_scene::npy::from_bytes(path, data.to_vec()) {
        let _ = array.rows3_f32();
        let _ = array.rows3_u32();
    }
});
